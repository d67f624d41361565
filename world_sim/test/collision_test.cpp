#include "world_sim/collision.h"

#include <gtest/gtest.h>

namespace world_sim {
namespace {

TEST(Collision, DiscAgainstAWallFace) {
  grid::OccupancyMap map(100, 100, 0.05);
  for (int j = 0; j < 100; ++j) map.set(60, j, grid::Cell::kOccupied);  // face at x = 3.0
  EXPECT_FALSE(DiscHitsWalls(map, {2.0, 2.0}, 0.075));
  EXPECT_FALSE(DiscHitsWalls(map, {2.925, 2.0}, 0.075));  // touching exactly
  EXPECT_TRUE(DiscHitsWalls(map, {2.93, 2.0}, 0.075));
}

TEST(Collision, DiscAgainstACornerUsesTrueDistance) {
  grid::OccupancyMap map(100, 100, 0.05);
  map.set(60, 60, grid::Cell::kOccupied);  // corner at (3.0, 3.0)
  // 0.07 m from the corner diagonally: the bounding boxes overlap but the disc does not.
  EXPECT_FALSE(DiscHitsWalls(map, {3.0 - 0.06, 3.0 - 0.06}, 0.075));
  EXPECT_TRUE(DiscHitsWalls(map, {3.0 - 0.05, 3.0 - 0.05}, 0.075));
}

TEST(Collision, MapEdgeIsAWall) {
  const grid::OccupancyMap map(100, 100, 0.05);
  EXPECT_TRUE(DiscHitsWalls(map, {0.05, 2.0}, 0.075));
  EXPECT_FALSE(DiscHitsWalls(map, {0.1, 2.0}, 0.075));
}

TEST(Collision, RayHitsDisc) {
  const auto t = RayHitsDisc({0.0, 0.0}, {1.0, 0.0}, {2.0, 0.0}, 0.5);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 1.5, 1e-12);
  EXPECT_FALSE(RayHitsDisc({0.0, 0.0}, {-1.0, 0.0}, {2.0, 0.0}, 0.5).has_value());
  EXPECT_FALSE(RayHitsDisc({0.0, 0.0}, {1.0, 0.0}, {2.0, 0.6}, 0.5).has_value());
  EXPECT_NEAR(*RayHitsDisc({2.0, 0.0}, {1.0, 0.0}, {2.0, 0.0}, 0.5), 0.0, 1e-12);
}

}  // namespace
}  // namespace world_sim
