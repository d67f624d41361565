#include "audio_propagation/corner_shadows.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "audio_propagation/diffraction_points.h"
#include "grid/line_of_sight.h"

namespace audio_propagation {
namespace {

std::vector<Eigen::Vector2d> CornerPositions(const grid::OccupancyMap& map) {
  std::vector<Eigen::Vector2d> out;
  for (const Corner& c : CornerVertices(map, FindDiffractionPoints(map, DiffractionRule::kMasks)))
    out.push_back(c.position);
  return out;
}

TEST(PseudoAngle, FollowsTheTrueAngleRoundTheCircle) {
  EXPECT_DOUBLE_EQ(PseudoAngle(1.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(PseudoAngle(0.0, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(PseudoAngle(-3.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(PseudoAngle(0.0, -1.0), 3.0);
  EXPECT_DOUBLE_EQ(PseudoAngle(1.0, 1.0), 0.5);
  double previous = -1.0;
  for (int k = 0; k < 3600; ++k) {
    const double a = 2.0 * M_PI * k / 3600.0;
    const double p = PseudoAngle(std::cos(a) * 7.0, std::sin(a) * 7.0);
    EXPECT_GT(p, previous) << "at " << a;
    EXPECT_LT(p, 4.0);
    previous = p;
  }
}

// 20 x 20 cells with a wall along x in [10, 11) from y = 0 up to y = 15.
TEST(CornerShadows, HidesWhatIsBehindTheWallAndNothingInView) {
  grid::OccupancyMap map(20, 20, 1.0);
  for (int j = 0; j < 15; ++j) map.set(10, j, grid::Cell::kOccupied);
  const std::vector<Eigen::Vector2d> corners = {{10.0, 15.0}, {11.0, 15.0}};
  const CornerShadows shadows(map, corners);
  // The top-left corner of the wall, seen from low on the far side: through the wall.
  EXPECT_TRUE(shadows.Hidden(0, {15.5, 5.5}));
  EXPECT_TRUE(shadows.Hidden(0, {19.5, 0.5}));
  // In view: on its own side, and above the wall.
  EXPECT_FALSE(shadows.Hidden(0, {5.5, 5.5}));
  EXPECT_FALSE(shadows.Hidden(0, {15.5, 18.5}));
  // Along the wall's top face, which the exact rules leave clear.
  EXPECT_FALSE(shadows.Hidden(0, {19.0, 15.0}));
  // The top-right corner, from low on the left: through the wall.
  EXPECT_TRUE(shadows.Hidden(1, {2.5, 3.5}));
  EXPECT_FALSE(shadows.Hidden(1, {15.5, 3.5}));
  EXPECT_GT(shadows.CoveredFraction(), 0.0);
}

// A random office-like map: an outer wall, and walls two or three cells thick with doorways.
grid::OccupancyMap RandomRooms(std::mt19937& rng) {
  const int w = 120, h = 80;
  grid::OccupancyMap map(w, h, 0.05);
  std::uniform_int_distribution<int> thick(1, 3), pick_x(5, w - 6), pick_y(5, h - 6), len(10, 60);
  for (int k = 0; k < 12; ++k) {
    const bool horizontal = k % 2 == 0;
    const int x = pick_x(rng), y = pick_y(rng), n = len(rng), t = thick(rng);
    const int door = std::uniform_int_distribution<int>(0, n)(rng);
    for (int a = 0; a < n; ++a) {
      if (a >= door && a < door + 8) continue;
      for (int b = 0; b < t; ++b) {
        const int i = horizontal ? x + a : x + b, j = horizontal ? y + b : y + a;
        if (map.InBounds(i, j)) map.set(i, j, grid::Cell::kOccupied);
      }
    }
  }
  for (int i = 0; i < w; ++i) map.set(i, 0, grid::Cell::kOccupied), map.set(i, h - 1, grid::Cell::kOccupied);
  for (int j = 0; j < h; ++j) map.set(0, j, grid::Cell::kOccupied), map.set(w - 1, j, grid::Cell::kOccupied);
  return map;
}

TEST(CornerShadows, NeverHidesACornerThatIsInSightOnRandomMaps) {
  std::mt19937 rng(7);
  int hidden = 0, blocked = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const grid::OccupancyMap map = RandomRooms(rng);
    const std::vector<Eigen::Vector2d> corners = CornerPositions(map);
    ASSERT_FALSE(corners.empty());
    const CornerShadows shadows(map, corners, 2);
    std::uniform_real_distribution<double> ux(0.0, map.width()), uy(0.0, map.height());
    for (int s = 0; s < 200; ++s) {
      Eigen::Vector2d p(ux(rng), uy(rng));
      if (map.Blocks(static_cast<int>(p.x()), static_cast<int>(p.y()))) continue;
      // Sometimes exactly on a grid line, or on a wall face, where grazes are decided.
      if (s % 4 == 0) p.x() = std::round(p.x());
      for (std::size_t k = 0; k < corners.size(); ++k) {
        const bool sight = !grid::FirstBlockedInCells(map, p, corners[k]).has_value();
        blocked += !sight;
        if (shadows.Hidden(k, p)) {
          ++hidden;
          ASSERT_FALSE(sight) << "corner " << corners[k].transpose() << " is in sight of " << p.transpose();
        }
      }
    }
  }
  // And it does its job: most corners out of sight are known to be without a walk.
  EXPECT_GT(hidden, blocked / 2) << hidden << " of " << blocked;
}

}  // namespace
}  // namespace audio_propagation
