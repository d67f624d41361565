#include "grid/occupancy_map.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace grid {
namespace {

TEST(OccupancyMap, RejectsBadSizeAndResolution) {
  EXPECT_THROW(OccupancyMap(0, 5, 0.1), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(5, -1, 0.1), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(5, 5, 0.0), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(5, 5, -0.5), std::invalid_argument);
}

TEST(OccupancyMap, WorldToCellWithOffsetOrigin) {
  const OccupancyMap map(10, 20, 0.5, {1.0, -2.0, 0.0});
  EXPECT_EQ(map.WorldToCell({1.0, -2.0}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(map.WorldToCell({1.49, -1.51}), Eigen::Vector2i(0, 0));
  EXPECT_EQ(map.WorldToCell({1.5, -1.5}), Eigen::Vector2i(1, 1));
  EXPECT_EQ(map.WorldToCell({0.99, -2.0}), Eigen::Vector2i(-1, 0));
  const Eigen::Vector2d centre = map.CellCenter(3, 4);
  EXPECT_NEAR(centre.x(), 1.0 + 3.5 * 0.5, 1e-12);
  EXPECT_NEAR(centre.y(), -2.0 + 4.5 * 0.5, 1e-12);
  EXPECT_EQ(map.WorldToCell(centre), Eigen::Vector2i(3, 4));
}

TEST(OccupancyMap, RotatedOriginRoundTrips) {
  const OccupancyMap map(10, 10, 0.1, {2.0, 3.0, M_PI / 2});
  // With the map turned a quarter turn, its +i axis points along world +y.
  const Eigen::Vector2d w = map.CellCoordsToWorld({5.0, 0.0});
  EXPECT_NEAR(w.x(), 2.0, 1e-12);
  EXPECT_NEAR(w.y(), 3.5, 1e-12);
  const Eigen::Vector2d back = map.WorldToCellCoords(w);
  EXPECT_NEAR(back.x(), 5.0, 1e-9);
  EXPECT_NEAR(back.y(), 0.0, 1e-9);
  EXPECT_EQ(map.WorldToCell(map.CellCenter(7, 2)), Eigen::Vector2i(7, 2));
}

TEST(OccupancyMap, OffMapBlocks) {
  OccupancyMap map(4, 4, 1.0);
  EXPECT_FALSE(map.Blocks(0, 0));
  EXPECT_TRUE(map.Blocks(-1, 0));
  EXPECT_TRUE(map.Blocks(4, 0));
  map.set(1, 2, Cell::kUnknown);
  EXPECT_TRUE(map.Blocks(1, 2));
  map.set(2, 2, Cell::kOccupied);
  EXPECT_TRUE(map.Blocks(2, 2));
  EXPECT_FALSE(map.IsFreeAt({2.5, 2.5}));
  EXPECT_TRUE(map.IsFreeAt({0.5, 0.5}));
  EXPECT_FALSE(map.IsFreeAt({-0.5, 0.5}));
}

}  // namespace
}  // namespace grid
