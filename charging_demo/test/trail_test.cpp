#include "charging_demo/trail.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace charging_demo {
namespace {

TEST(Trail, LaysACrumbEverySpacingAndKeepsIndicesWhenTheOldestDrop) {
  TrailOptions o;
  o.spacing = 1.0;
  o.capacity = 3;
  Trail trail(o);
  EXPECT_TRUE(trail.empty());
  for (int k = 0; k <= 40; ++k) trail.Visit({0.1 * k, 0.0}, k);  // 4 m in steps of 0.1 m
  // Crumbs at 0, 1, 2, 3 and 4 m; the capacity keeps the last three.
  EXPECT_EQ(trail.oldest(), 2u);
  EXPECT_EQ(trail.newest(), 4u);
  EXPECT_NEAR(trail.at(2).position.x(), 2.0, 1e-9);
  EXPECT_NEAR(trail.at(4).position.x(), 4.0, 1e-9);
  EXPECT_DOUBLE_EQ(trail.at(3).time, 30.0);
}

TEST(Trail, FindsTheCrumbLaidByATime) {
  Trail trail({});
  for (int k = 0; k < 5; ++k) trail.Visit({k, 0.0}, 10.0 * k);
  EXPECT_EQ(trail.LaidBy(25.0), std::optional<std::uint64_t>(2));
  EXPECT_EQ(trail.LaidBy(20.0), std::optional<std::uint64_t>(2));
  EXPECT_EQ(trail.LaidBy(1e9), std::optional<std::uint64_t>(4));
  EXPECT_FALSE(trail.LaidBy(-1.0));
}

TEST(Trail, GoesAsFarBackAsItCanWithinReach) {
  Trail trail({});
  // Out along x and back along y = 1: crumb 0 at (0, 0), the way back passes next to it.
  for (int k = 0; k <= 5; ++k) trail.Visit({k, 0.0}, k);
  for (int k = 5; k >= 0; --k) trail.Visit({k, 1.0}, 11.0 - k);
  const std::uint64_t newest = trail.newest();
  const auto anything = [](const Eigen::Vector2d&) { return true; };
  // From the end of the way back, (0, 0) is the furthest back within 1.5 m.
  EXPECT_EQ(trail.FurthestBack(newest, 0, {0.0, 1.0}, 1.5, anything), std::optional<std::uint64_t>(0));
  // Not before `to`.
  EXPECT_EQ(trail.FurthestBack(newest, 3, {0.0, 1.0}, 1.5, anything), std::optional<std::uint64_t>(newest - 1));
  // A wall along y = 0.5 (the caller's check) leaves only the crumbs on its own side.
  const auto above = [](const Eigen::Vector2d& p) { return p.y() > 0.5; };
  EXPECT_EQ(trail.FurthestBack(newest, 0, {0.0, 1.0}, 1.5, above), std::optional<std::uint64_t>(newest - 1));
  EXPECT_FALSE(trail.FurthestBack(newest, 0, {20.0, 20.0}, 1.5, anything));
}

TEST(Trail, RefusesImpossibleOptions) {
  TrailOptions o;
  o.spacing = 0.0;
  EXPECT_THROW(Trail{o}, std::invalid_argument);
  o = {};
  o.capacity = 1;
  EXPECT_THROW(Trail{o}, std::invalid_argument);
}

}  // namespace
}  // namespace charging_demo
