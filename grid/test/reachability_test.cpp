#include "grid/reachability.h"

#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace grid {
namespace {

// 3 m x 1.2 m at 0.1 m, walled round, split by a wall at column 10 into a small room on the left
// (columns 1-9) and a larger one on the right (columns 11-28).
OccupancyMap TwoRooms() {
  OccupancyMap map(30, 12, 0.1);
  for (int i = 0; i < map.width(); ++i) {
    map.set(i, 0, Cell::kOccupied);
    map.set(i, map.height() - 1, Cell::kOccupied);
  }
  for (int j = 0; j < map.height(); ++j) {
    map.set(0, j, Cell::kOccupied);
    map.set(10, j, Cell::kOccupied);
    map.set(map.width() - 1, j, Cell::kOccupied);
  }
  return map;
}

TEST(Reachability, WallsSplitRegionsAndDiscsKeepOffWalls) {
  const OccupancyMap map = TwoRooms();
  const Reachability room(map, 0.15);
  const int left = room.Region({0.55, 0.55});
  const int right = room.Region({2.05, 0.55});
  EXPECT_GT(left, 0);
  EXPECT_GT(right, 0);
  EXPECT_NE(left, right);
  EXPECT_EQ(room.largest(), right);
  EXPECT_EQ(room.Region({1.05, 0.55}), 0);   // in the wall
  EXPECT_EQ(room.Region({0.15, 0.55}), 0);   // free, but 0.1 m from a wall: no room for the disc
  EXPECT_EQ(room.Region({-1.0, 0.55}), 0);   // off the map
}

TEST(Reachability, SamplesComeFromTheRegionAsked) {
  const OccupancyMap map = TwoRooms();
  const Reachability room(map, 0.15);
  std::mt19937 rng(3);
  for (int k = 0; k < 50; ++k) {
    const Eigen::Vector2d p = room.Sample(room.largest(), rng);
    EXPECT_EQ(room.Region(p), room.largest()) << p.transpose();
    EXPECT_GT(p.x(), 1.1);
  }
}

TEST(Reachability, NoRoomForTheDiscAnywhere) {
  const OccupancyMap map = TwoRooms();
  const Reachability room(map, 0.6);  // wider than either room
  EXPECT_EQ(room.largest(), 0);
  std::mt19937 rng(3);
  EXPECT_THROW(room.Sample(room.largest(), rng), std::invalid_argument);
}

}  // namespace
}  // namespace grid
