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

// Found by fuzz/world_file.cpp: a robot at y = 4.3e10 m made WorldToCell convert a number beyond
// int's range (undefined behaviour; on x86 it came out as INT_MIN, "off the map" by luck). Points
// beyond int's reach, infinite or NaN must land on a cell off the map on the right side.
TEST(OccupancyMap, FarAndNonFinitePointsAreOffTheMap) {
  const OccupancyMap map(10, 20, 0.5, {1.0, -2.0, 0.0});
  const Eigen::Vector2i far = map.WorldToCell({1.5, 42949672961.5});
  EXPECT_EQ(far.x(), 1);
  EXPECT_GE(far.y(), map.height());
  EXPECT_LT(map.WorldToCell({-1e300, 0.0}).x(), 0);
  EXPECT_GE(map.WorldToCell({HUGE_VAL, 0.0}).x(), map.width());
  const Eigen::Vector2i nan = map.WorldToCell({std::nan(""), 0.0});
  EXPECT_FALSE(map.InBounds(nan.x(), nan.y()));
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(1.5, 4.3e10), Eigen::Vector2d(-4.3e10, 0.0),
                                  Eigen::Vector2d(std::nan(""), 1.0), Eigen::Vector2d(1.5, -HUGE_VAL)}) {
    EXPECT_FALSE(map.IsFreeAt(p)) << p.transpose();
  }
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

TEST(OccupancyMap, CellsAcrossASquareRoundUpButNotAWholeNumber) {
  EXPECT_EQ(CellsAcross(OccupancyMap(10, 10, 0.05), 0.25), 5);   // exactly five cells
  EXPECT_EQ(CellsAcross(OccupancyMap(10, 10, 0.1), 0.25), 3);    // 2.5 cells: three
  EXPECT_EQ(CellsAcross(OccupancyMap(10, 10, 0.5), 0.25), 1);    // under a cell: one
}

}  // namespace
}  // namespace grid
