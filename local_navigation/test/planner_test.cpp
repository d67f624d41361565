#include "local_navigation/planner.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace local_navigation {
namespace {

// A map of `size` x `size` cells of 1 m with cell (0, 0) at the lower left.
LocalMap Map(int size) {
  LocalMap map(LocalMapOptions{size, 1.0, 1000.0});
  map.Recentre({size / 2 + 0.5, size / 2 + 0.5});
  return map;
}

PlannerOptions NoRisk() {
  PlannerOptions o;
  o.robot_radius = 0.0;
  o.risk_scale = 0.0;
  return o;
}

TEST(Planner, GrowsObstaclesByADisc) {
  LocalMap map = Map(5);
  map.Set({2, 2}, CellState::kOccupied, 0.0);
  const Grid<std::uint8_t> grown = GrowObstacles(map, 1);
  int count = 0;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) count += grown.at({x, y}) != 0;
  EXPECT_EQ(count, 5);  // radius 1: the cell and its 4 neighbours, not the diagonals
  EXPECT_TRUE(grown.at({1, 2}) && grown.at({3, 2}) && grown.at({2, 1}) && grown.at({2, 3}));
  EXPECT_FALSE(grown.at({1, 1}));
  EXPECT_EQ(GrowObstacles(map, 2).at({1, 1}), 255);  // sqrt(2) <= 2
}

TEST(Planner, ManhattanDistanceMatchesHandCount) {
  LocalMap map = Map(5);
  map.Set({2, 2}, CellState::kOccupied, 0.0);
  const Grid<int> d = ManhattanDistance(GrowObstacles(map, 1));
  // Nearest obstacle from each cell of row y = 0, then y = 4, then column x = 0.
  const int row0[5] = {3, 2, 1, 2, 3};
  for (int x = 0; x < 5; ++x) EXPECT_EQ(d.at({x, 0}), row0[x]) << x;
  for (int x = 0; x < 5; ++x) EXPECT_EQ(d.at({x, 4}), row0[x]) << x;
  EXPECT_EQ(d.at({0, 2}), 1);
  EXPECT_EQ(d.at({1, 1}), 1);
  EXPECT_EQ(d.at({2, 2}), 0);
  EXPECT_EQ(d.at({1, 2}), 0);
}

// A wall at x = 2 from y = 0 to 3 with the gap at y = 4:
//   y=4  . . . . .
//   y=3  . . # . .
//   y=2  . . # . .
//   y=1  . . # . .
//   y=0  G . # . S
LocalMap WallMap() {
  LocalMap map = Map(5);
  for (int y = 0; y < 4; ++y) map.Set({2, y}, CellState::kOccupied, 0.0);
  return map;
}

TEST(Planner, WavefrontCountsStepsAroundTheWall) {
  const LocalMap map = WallMap();
  const Grid<std::uint8_t> grown = GrowObstacles(map, 0);
  const Grid<std::uint32_t> costs = StepCosts(map, grown, ManhattanDistance(grown), NoRisk());
  const Grid<std::uint32_t> p = Wavefront(costs, {0, 0});
  // Tenths of a step: 10 per cell moved.
  EXPECT_EQ(p.at({0, 0}), 0u);
  EXPECT_EQ(p.at({1, 0}), 10u);
  EXPECT_EQ(p.at({1, 4}), 50u);
  EXPECT_EQ(p.at({2, 4}), 60u);
  EXPECT_EQ(p.at({3, 4}), 70u);
  EXPECT_EQ(p.at({3, 0}), 110u);
  EXPECT_EQ(p.at({4, 0}), 120u);
  EXPECT_EQ(p.at({2, 0}), kUnreachable);
}

TEST(Planner, RiskAddsTheExponentialOfTheDistance) {
  const LocalMap map = WallMap();
  PlannerOptions o = NoRisk();
  o.risk_scale = 2.0;
  o.risk_decay = 1.0;
  const Grid<std::uint8_t> grown = GrowObstacles(map, 0);
  const Grid<std::uint32_t> costs = StepCosts(map, grown, ManhattanDistance(grown), o);
  // (1, 0) is 1 from the wall: 10 + round(10 * 2 * e^-1) = 10 + 7; (0, 0) is 2 away: 10 + 3.
  EXPECT_EQ(costs.at({1, 0}), 17u);
  EXPECT_EQ(costs.at({0, 0}), 13u);
  EXPECT_EQ(costs.at({2, 1}), kUnreachable);
}

TEST(Planner, SteepestDescentWalksAroundTheWallToTheGoal) {
  const Plan plan = MakePlan(WallMap(), {4, 0}, {0, 0}, NoRisk());
  ASSERT_EQ(plan.cells.size(), 13u);  // 12 steps
  EXPECT_EQ(plan.cells.front(), Eigen::Vector2i(4, 0));
  EXPECT_EQ(plan.cells.back(), Eigen::Vector2i(0, 0));
  for (std::size_t i = 1; i < plan.cells.size(); ++i) {
    EXPECT_EQ((plan.cells[i] - plan.cells[i - 1]).cwiseAbs().sum(), 1);
    EXPECT_LT(plan.potential.at(plan.cells[i]), plan.potential.at(plan.cells[i - 1]));
  }
  EXPECT_TRUE(std::any_of(plan.cells.begin(), plan.cells.end(),
                          [](const Eigen::Vector2i& c) { return c == Eigen::Vector2i(2, 4); }));
}

TEST(Planner, NoPathThroughAClosedWall) {
  LocalMap map = WallMap();
  map.Set({2, 4}, CellState::kOccupied, 0.0);
  EXPECT_TRUE(MakePlan(map, {4, 0}, {0, 0}, NoRisk()).cells.empty());
  // A goal inside the wall is reached from its free side (a marker drawn against a wall).
  const Plan in_wall = MakePlan(map, {4, 0}, {2, 2}, NoRisk());
  ASSERT_EQ(in_wall.cells.size(), 5u);
  EXPECT_EQ(in_wall.cells[3], Eigen::Vector2i(3, 2));
  EXPECT_EQ(in_wall.cells.back(), Eigen::Vector2i(2, 2));
}

// Whether `goal` can be reached from `start` over 4-connected cells that are not occupied,
// by a plain breadth-first search (independent of the planner).
bool Reachable(const LocalMap& map, const Eigen::Vector2i& start, const Eigen::Vector2i& goal) {
  std::vector<bool> seen(static_cast<std::size_t>(map.size()) * map.size(), false);
  std::vector<Eigen::Vector2i> queue{start};
  seen[start.y() * map.size() + start.x()] = true;
  for (std::size_t i = 0; i < queue.size(); ++i) {
    if (queue[i] == goal) return true;
    for (const Eigen::Vector2i& step : {Eigen::Vector2i(1, 0), Eigen::Vector2i(-1, 0),
                                       Eigen::Vector2i(0, 1), Eigen::Vector2i(0, -1)}) {
      const Eigen::Vector2i next = queue[i] + step;
      if (!map.Inside(next) || seen[next.y() * map.size() + next.x()]) continue;
      if (map.at(next) == CellState::kOccupied && next != goal) continue;
      seen[next.y() * map.size() + next.x()] = true;
      queue.push_back(next);
    }
  }
  return false;
}

TEST(Planner, RiskKeepsThePathInTheMiddleOfACorridor) {
  // Walls on rows 3 and 7; the corridor is rows 4..6.
  LocalMap map = Map(11);
  for (int x = 0; x < 11; ++x) {
    map.Set({x, 3}, CellState::kOccupied, 0.0);
    map.Set({x, 7}, CellState::kOccupied, 0.0);
  }
  PlannerOptions o = NoRisk();
  o.risk_scale = 8.0;
  const Plan plan = MakePlan(map, {0, 4}, {10, 4}, o);
  ASSERT_FALSE(plan.cells.empty());
  int middle = 0;
  for (const Eigen::Vector2i& c : plan.cells) middle += c.y() == 5;
  EXPECT_GE(middle, 8);  // moves to the centre line, and back only at the end
}

TEST(Planner, DescentAlwaysReachesAReachableGoalOnRandomMaps) {
  std::mt19937 rng(7);
  PlannerOptions o;
  o.robot_radius = 0.2;
  int reached = 0;
  for (int trial = 0; trial < 200; ++trial) {
    LocalMap map(LocalMapOptions{31, 0.15, 1000.0});
    map.Recentre({0.0, 0.0});
    std::uniform_int_distribution<int> cell(0, 30);
    for (int k = 0; k < 120; ++k) map.Set({cell(rng), cell(rng)}, CellState::kOccupied, 0.0);
    const Eigen::Vector2i start(cell(rng), cell(rng)), goal(cell(rng), cell(rng));
    if (map.at(start) == CellState::kOccupied || map.at(goal) == CellState::kOccupied) continue;
    const Plan plan = MakePlan(map, start, goal, o);
    const bool reachable = Reachable(map, start, goal);
    ASSERT_EQ(!plan.cells.empty(), reachable) << trial;
    if (!reachable) continue;
    ++reached;
    EXPECT_EQ(plan.cells.back(), goal);
    for (const Eigen::Vector2i& c : plan.cells) EXPECT_NE(map.at(c), CellState::kOccupied);
  }
  EXPECT_GT(reached, 100);
}

TEST(Planner, RejectsImpossibleOptions) {
  PlannerOptions o;
  o.risk_decay = 0.0;
  EXPECT_THROW(ValidateOptions(o), std::invalid_argument);
  o = PlannerOptions();
  o.robot_radius = -0.1;
  EXPECT_THROW(ValidateOptions(o), std::invalid_argument);
}

}  // namespace
}  // namespace local_navigation
