#include "charging_demo/charger_search.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace charging_demo {
namespace {

local_navigation::LocalMap EmptyMap() {
  local_navigation::LocalMap map(local_navigation::LocalMapOptions{});
  map.Recentre({0.0, 0.0});
  return map;
}

TEST(ChargerSearch, CountsTimePerCell) {
  ChargerSearch search(SearchOptions{});
  search.Visit({0.2, 0.3}, 1.5);
  search.Visit({0.8, 0.9}, 2.0);  // the same 1 m cell
  search.Visit({-0.2, 0.3}, 4.0);
  EXPECT_DOUBLE_EQ(search.Visits({0.5, 0.5}), 3.5);
  EXPECT_DOUBLE_EQ(search.Visits({-0.5, 0.5}), 4.0);
  EXPECT_DOUBLE_EQ(search.Visits({5.0, 5.0}), 0.0);
}

TEST(ChargerSearch, HeadsForTheLeastVisitedSide) {
  SearchOptions o;
  o.directions = 4;  // east, north, west, south
  ChargerSearch search(o);
  // Long spells to the east, north and south: west is the new ground.
  for (double x = 0.5; x < 6.0; x += 1.0) search.Visit({x, 0.5}, 30.0);
  for (double y = 0.5; y < 6.0; y += 1.0) search.Visit({0.5, y}, 30.0), search.Visit({0.5, -y}, 30.0);
  std::mt19937 rng(1);
  const Eigen::Vector2d goal = search.ChooseGoal({0.0, 0.0}, EmptyMap(), rng);
  EXPECT_NEAR(goal.x(), -4.0, 1e-9);
  EXPECT_NEAR(goal.y(), 0.0, 1e-9);
  // That way just failed: the next best.
  const Eigen::Vector2d other = search.ChooseGoal({0.0, 0.0}, EmptyMap(), rng, M_PI);
  EXPECT_GT((other - goal).norm(), 1.0);
}

TEST(ChargerSearch, SkipsWaysTheMapShowsBlocked) {
  SearchOptions o;
  o.directions = 4;
  ChargerSearch search(o);
  local_navigation::LocalMap map = EmptyMap();
  // A wall 1 m to the west, and every other way visited a little.
  for (int dy = -3; dy <= 3; ++dy) map.Set(map.CellOf({-1.0, 0.15 * dy}), local_navigation::CellState::kOccupied, 0.0);
  search.Visit({4.0, 0.5}, 1.0);
  search.Visit({0.5, 4.0}, 1.0);
  search.Visit({0.5, -4.0}, 1.0);
  std::mt19937 rng(2);
  const Eigen::Vector2d goal = search.ChooseGoal({0.0, 0.0}, map, rng);
  EXPECT_GT(goal.x(), -1.0) << "went through the wall";
}

TEST(ChargerSearch, SpreadsItsChoicesWhenNothingIsKnown) {
  ChargerSearch search(SearchOptions{});
  std::mt19937 rng(3);
  int east = 0, west = 0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d goal = search.ChooseGoal({0.0, 0.0}, EmptyMap(), rng);
    EXPECT_NEAR(goal.norm(), 4.0, 1e-9);
    (goal.x() > 0 ? east : west) += 1;
  }
  EXPECT_GT(east, 50);
  EXPECT_GT(west, 50);
}

TEST(ChargerSearch, RejectsImpossibleOptions) {
  SearchOptions o;
  o.cell = 0.0;
  EXPECT_THROW(ChargerSearch{o}, std::invalid_argument);
  o = SearchOptions{};
  o.directions = 0;
  EXPECT_THROW(ChargerSearch{o}, std::invalid_argument);
}

}  // namespace
}  // namespace charging_demo
