#include "grid/line_of_sight.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace grid {
namespace {

// Unit cells at the world origin, so world metres equal cell coordinates.
OccupancyMap OpenMap(int w = 8, int h = 8) { return OccupancyMap(w, h, 1.0); }

TEST(LineOfSight, ClearInOpenSpace) {
  const OccupancyMap map = OpenMap();
  EXPECT_TRUE(LineOfSight(map, {0.5, 0.5}, {7.5, 6.2}));
  EXPECT_TRUE(LineOfSight(map, {3.3, 3.3}, {3.3, 3.3}));
}

TEST(LineOfSight, WallBlocksWhereTheSegmentEntersIt) {
  OccupancyMap map = OpenMap();
  map.set(2, 2, Cell::kOccupied);
  const auto t = FirstBlocked(map, {0.5, 2.5}, {4.5, 2.5});
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.375, 1e-12);
  EXPECT_FALSE(LineOfSight(map, {4.5, 2.5}, {0.5, 2.5}));
}

TEST(LineOfSight, ExactCornerGrazeIsClear) {
  OccupancyMap map = OpenMap();
  map.set(2, 2, Cell::kOccupied);
  // Slope 1 through the vertex (2, 3), the top-left corner of the wall cell.
  EXPECT_TRUE(LineOfSight(map, {0.5, 1.5}, {3.5, 4.5}));
  EXPECT_TRUE(LineOfSight(map, {3.5, 4.5}, {0.5, 1.5}));
  // Through the bottom-right corner (3, 2), with world coordinates that are not exact binary
  // fractions on a fine map.
  OccupancyMap fine(100, 100, 0.05);
  fine.set(40, 40, Cell::kOccupied);  // covers [2.0, 2.05] x [2.0, 2.05]
  EXPECT_TRUE(LineOfSight(fine, {2.05 - 0.35, 2.0 - 0.35}, {2.05 + 0.35, 2.0 + 0.35}));
  EXPECT_FALSE(LineOfSight(fine, {2.05 - 0.35, 2.0 - 0.349}, {2.05 + 0.35, 2.0 + 0.351}));
}

TEST(LineOfSight, DiagonalPinchIsBlocked) {
  OccupancyMap map = OpenMap();
  map.set(2, 2, Cell::kOccupied);
  map.set(1, 3, Cell::kOccupied);  // touches (2, 2) only at the vertex (2, 3)
  const auto t = FirstBlocked(map, {0.5, 1.5}, {3.5, 4.5});
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.5, 1e-12);
}

TEST(LineOfSight, AlongAWallFaceIsClearInsideAWallIsNot) {
  OccupancyMap map = OpenMap();
  for (int i = 0; i < 8; ++i) map.set(i, 2, Cell::kOccupied);
  EXPECT_TRUE(LineOfSight(map, {0.5, 2.0}, {7.5, 2.0}));  // on the face y = 2 of row 2
  EXPECT_TRUE(LineOfSight(map, {7.5, 3.0}, {0.5, 3.0}));  // on the face y = 3
  map.set(5, 1, Cell::kOccupied);                         // now a wall on both sides at x in [5, 6]
  const auto t = FirstBlocked(map, {0.5, 2.0}, {7.5, 2.0});
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t * 7.0, 4.5, 1e-9);
  // Vertical face, and a diagonal wall crossing the line at a vertex.
  OccupancyMap v = OpenMap();
  v.set(3, 1, Cell::kOccupied);
  EXPECT_TRUE(LineOfSight(v, {3.0, 0.5}, {3.0, 7.5}));
  v.set(2, 2, Cell::kOccupied);  // (3, 1) and (2, 2) meet at the vertex (3, 2)
  EXPECT_FALSE(LineOfSight(v, {3.0, 0.5}, {3.0, 7.5}));
}

TEST(LineOfSight, EndingOnAWallFaceIsClear) {
  OccupancyMap map = OpenMap();
  map.set(2, 0, Cell::kOccupied);
  EXPECT_TRUE(LineOfSight(map, {0.5, 0.5}, {2.0, 0.5}));
  EXPECT_FALSE(LineOfSight(map, {0.5, 0.5}, {2.01, 0.5}));
}

TEST(LineOfSight, LeavingTheMapIsBlocked) {
  const OccupancyMap map = OpenMap();
  EXPECT_FALSE(LineOfSight(map, {0.5, 0.5}, {-0.5, 0.5}));
  EXPECT_FALSE(LineOfSight(map, {0.5, 0.5}, {0.5, 9.0}));
}

TEST(LineOfSight, UnknownCellsBlock) {
  OccupancyMap map = OpenMap();
  map.set(3, 3, Cell::kUnknown);
  EXPECT_FALSE(LineOfSight(map, {0.5, 3.5}, {7.5, 3.5}));
}

TEST(LineOfSight, NoRandomSegmentCrossesADiagonalWall) {
  // A one-cell diagonal wall whose cells touch only at corners.
  OccupancyMap map(40, 40, 1.0);
  for (int i = 0; i < 40; ++i) map.set(i, i, Cell::kOccupied);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 40.0);
  int tried = 0;
  while (tried < 2000) {
    const Eigen::Vector2d a(u(rng), u(rng)), b(u(rng), u(rng));
    const bool a_below = a.y() < a.x() - 1.0, b_above = b.y() > b.x() + 1.0;
    if (!a_below || !b_above) continue;
    ++tried;
    ASSERT_FALSE(LineOfSight(map, a, b)) << a.transpose() << " -> " << b.transpose();
  }
  // Segments along the wall's own diagonal vertices, on the free side, stay clear.
  EXPECT_TRUE(LineOfSight(map, {1.0, 0.0}, {39.0, 38.0}));
}

TEST(LineOfSight, SymmetricOnRandomMaps) {
  std::mt19937 rng(11);
  std::bernoulli_distribution wall(0.15);
  OccupancyMap map(30, 30, 0.1);
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 30; ++i)
      if (wall(rng)) map.set(i, j, Cell::kOccupied);
  std::uniform_int_distribution<int> cell(0, 29);
  for (int k = 0; k < 3000; ++k) {
    const int ai = cell(rng), aj = cell(rng), bi = cell(rng), bj = cell(rng);
    if (map.Blocks(ai, aj) || map.Blocks(bi, bj)) continue;
    const Eigen::Vector2d a = map.CellCenter(ai, aj), b = map.CellCenter(bi, bj);
    ASSERT_EQ(LineOfSight(map, a, b), LineOfSight(map, b, a)) << ai << "," << aj << " " << bi
                                                              << "," << bj;
  }
}

TEST(CastRay, RangesToAKnownWall) {
  OccupancyMap map(100, 100, 0.05);
  for (int j = 0; j < 100; ++j) map.set(80, j, Cell::kOccupied);  // wall face at x = 4.0
  const auto r = CastRay(map, {1.0, 2.5}, 0.0, 5.0);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r, 3.0, 1e-9);
  const auto slanted = CastRay(map, {1.0, 0.5}, M_PI / 4, 10.0);
  ASSERT_TRUE(slanted.has_value());
  EXPECT_NEAR(*slanted, 3.0 * std::sqrt(2.0), 1e-9);
  EXPECT_FALSE(CastRay(map, {1.0, 2.5}, 0.0, 2.5).has_value());
  const auto back = CastRay(map, {1.0, 2.5}, M_PI, 5.0);  // the map's edge at x = 0
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(*back, 1.0, 1e-9);
}

TEST(CastRay, WorksOnARotatedMap) {
  OccupancyMap map(100, 100, 0.05, {0.0, 0.0, M_PI / 2});
  for (int j = 0; j < 100; ++j) map.set(80, j, Cell::kOccupied);  // map +i is world +y
  const auto r = CastRay(map, {-2.5, 1.0}, M_PI / 2, 5.0);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r, 3.0, 1e-9);
}

}  // namespace
}  // namespace grid
