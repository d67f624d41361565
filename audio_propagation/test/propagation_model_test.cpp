#include "audio_propagation/propagation_model.h"

#include <cmath>
#include <limits>
#include <queue>
#include <random>

#include <gtest/gtest.h>

#include "grid/line_of_sight.h"

namespace audio_propagation {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

PropagationOptions Unlimited(DiffractionRule rule = DiffractionRule::kMasks) {
  PropagationOptions o;
  o.rule = rule;
  o.source_level_db = 1000.0;  // hear everything: these tests are about geometry
  o.threshold_db = -1000.0;
  o.threads = 1;
  return o;
}

// 20 x 20 cells of 1 m with a wall along x in [10, 11) from y = 0 up to y = 15.
grid::OccupancyMap WallWithGapAbove() {
  grid::OccupancyMap map(20, 20, 1.0);
  for (int j = 0; j < 15; ++j) map.set(10, j, grid::Cell::kOccupied);
  return map;
}

TEST(PropagationModel, DirectLineOfSight) {
  const PropagationModel model(grid::OccupancyMap(20, 20, 1.0), Unlimited());
  const SoundPath p = model.Path({2.0, 3.0}, {5.0, 7.0});
  ASSERT_TRUE(p.reachable);
  EXPECT_NEAR(p.length, 5.0, 1e-9);
  EXPECT_EQ(p.bends, 0);
  EXPECT_NEAR(p.arrival_angle, std::atan2(-4.0, -3.0), 1e-9);  // it comes from the source
}

TEST(PropagationModel, AroundOneCorner) {
  const PropagationModel model(WallWithGapAbove(), Unlimited(DiffractionRule::kConvexCorners));
  // Around the top end of the wall: it bends at the wall's two top corners, (10, 15) and (11, 15).
  const Eigen::Vector2d s(5.5, 5.5), r(15.5, 5.5);
  const SoundPath p = model.Path(s, r);
  ASSERT_TRUE(p.reachable);
  const Eigen::Vector2d a(10.0, 15.0), b(11.0, 15.0);
  const double expected = (a - s).norm() + (b - a).norm() + (r - b).norm();
  EXPECT_NEAR(p.length, expected, 1e-4);
  EXPECT_EQ(p.bends, 2);
  // It arrives from above-left at the receiver: from b.
  EXPECT_NEAR(p.arrival_angle, std::atan2(b.y() - r.y(), b.x() - r.x()), 1e-6);
  // Never shorter than the straight line.
  EXPECT_GT(p.length, (r - s).norm());
}

TEST(PropagationModel, AroundTwoCornersAndThroughADoorway) {
  // Two walls: one from the bottom with a gap at the top, one from the top with a gap at the
  // bottom; sound zig-zags between them.
  grid::OccupancyMap map(30, 20, 1.0);
  for (int j = 0; j < 16; ++j) map.set(10, j, grid::Cell::kOccupied);
  for (int j = 4; j < 20; ++j) map.set(20, j, grid::Cell::kOccupied);
  const PropagationModel model(map, Unlimited(DiffractionRule::kConvexCorners));
  const Eigen::Vector2d s(5.5, 5.5), r(25.5, 15.5);
  const SoundPath p = model.Path(s, r);
  ASSERT_TRUE(p.reachable);
  const Eigen::Vector2d c1(10.0, 16.0), c2(11.0, 16.0), c3(20.0, 4.0), c4(21.0, 4.0);
  const double expected = (c1 - s).norm() + (c2 - c1).norm() + (c3 - c2).norm() + (c4 - c3).norm() + (r - c4).norm();
  EXPECT_NEAR(p.length, expected, 1e-4);
  EXPECT_EQ(p.bends, 4);

  // A doorway: a full wall with a one-cell gap at y in [8, 9).
  grid::OccupancyMap door(20, 20, 1.0);
  for (int j = 0; j < 20; ++j)
    if (j != 8) door.set(10, j, grid::Cell::kOccupied);
  const PropagationModel through(door, Unlimited(DiffractionRule::kMasks));
  const SoundPath d = through.Path({5.5, 8.5}, {15.5, 8.5});
  ASSERT_TRUE(d.reachable);
  EXPECT_NEAR(d.length, 10.0, 1e-9);  // straight through the gap
  const SoundPath bent = through.Path({5.5, 2.5}, {15.5, 2.5});
  ASSERT_TRUE(bent.reachable);
  // Up to the gap's lower corners (10, 8) and (11, 8), across, and down again.
  EXPECT_NEAR(bent.length, 2.0 * std::hypot(4.5, 5.5) + 1.0, 1e-4);
  EXPECT_EQ(bent.bends, 2);
}

TEST(PropagationModel, NoPathIntoAClosedRoom) {
  grid::OccupancyMap map(20, 20, 1.0);
  for (int k = 8; k <= 14; ++k) {
    map.set(k, 8, grid::Cell::kOccupied);
    map.set(k, 14, grid::Cell::kOccupied);
    map.set(8, k, grid::Cell::kOccupied);
    map.set(14, k, grid::Cell::kOccupied);
  }
  const PropagationModel model(map, Unlimited());
  EXPECT_FALSE(model.Path({2.5, 2.5}, {11.5, 11.5}).reachable);
  EXPECT_TRUE(model.Path({9.5, 9.5}, {12.5, 12.5}).reachable);
}

TEST(PropagationModel, LevelThresholdAndTravelTime) {
  PropagationOptions o;
  o.source_level_db = 60.0;
  o.threshold_db = 40.0;  // heard up to 10 m
  o.threads = 1;
  const PropagationModel model(grid::OccupancyMap(40, 10, 0.5), o);
  EXPECT_NEAR(model.HearingDistance(), 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(model.LevelAt(0.5), 60.0);  // inside d0 the level is the source level
  EXPECT_NEAR(model.LevelAt(2.0), 60.0 - 20.0 * std::log10(2.0), 1e-12);
  const SoundPath near = model.Path({1.0, 2.0}, {5.0, 2.0});
  ASSERT_TRUE(near.audible);
  EXPECT_NEAR(near.level_db, 60.0 - 20.0 * std::log10(4.0), 1e-9);
  EXPECT_NEAR(near.travel_time, 4.0 / 343.0, 1e-12);
  EXPECT_FALSE(model.Path({1.0, 2.0}, {12.0, 2.0}).audible);  // 11 m: below the threshold

  o.max_range = 3.0;
  const PropagationModel ranged(grid::OccupancyMap(40, 10, 0.5), o);
  EXPECT_FALSE(ranged.Path({1.0, 2.0}, {5.0, 2.0}).reachable);
}

TEST(PropagationModel, ImpossibleOptionsAreRejected) {
  PropagationOptions o;
  o.max_range = -1.0;
  EXPECT_THROW(ValidateOptions(o), std::invalid_argument);
  o = {};
  o.threshold_db = o.source_level_db + 1.0;
  EXPECT_THROW(ValidateOptions(o), std::invalid_argument);
  o = {};
  o.speed_of_sound = 0.0;
  EXPECT_THROW(ValidateOptions(o), std::invalid_argument);
}

TEST(PropagationModel, ComputeServesEveryListenerOfEverySource) {
  const PropagationModel model(WallWithGapAbove(), Unlimited());
  const std::vector<Eigen::Vector2d> at = {{5.5, 5.5}, {15.5, 5.5}, {5.5, 12.5}};
  const auto paths = model.Compute(at, {true, false, true});
  EXPECT_FALSE(paths[0][0].reachable);
  EXPECT_TRUE(paths[0][1].reachable);
  EXPECT_TRUE(paths[0][2].reachable);
  EXPECT_FALSE(paths[1][0].reachable);  // robot 1 is not transmitting
  EXPECT_NEAR(paths[2][1].length, model.Path(at[2], at[1]).length, 1e-9);
  EXPECT_NEAR(paths[0][1].length, model.Path(at[1], at[0]).length, 1e-4);  // symmetric
}

// Independent reference: Dijkstra over the visibility graph of every corner of every free cell
// plus the two end points, with the same exact line of sight. Corners where two diagonally
// opposite cells block are left out: a path through one would squeeze through a diagonal wall.
double BruteForce(const grid::OccupancyMap& map, const Eigen::Vector2d& s, const Eigen::Vector2d& r) {
  std::vector<Eigen::Vector2d> nodes = {s, r};
  for (int j = 0; j <= map.height(); ++j)
    for (int i = 0; i <= map.width(); ++i)
      if ((!map.Blocks(i, j) || !map.Blocks(i - 1, j) || !map.Blocks(i, j - 1) || !map.Blocks(i - 1, j - 1)) &&
          !(map.Blocks(i, j) && map.Blocks(i - 1, j - 1)) && !(map.Blocks(i - 1, j) && map.Blocks(i, j - 1)))
        nodes.push_back(map.CellCoordsToWorld(Eigen::Vector2d(i, j)));
  std::vector<double> dist(nodes.size(), kInf);
  std::vector<bool> done(nodes.size(), false);
  dist[0] = 0.0;
  for (std::size_t it = 0; it < nodes.size(); ++it) {
    std::size_t u = nodes.size();
    for (std::size_t k = 0; k < nodes.size(); ++k)
      if (!done[k] && dist[k] < kInf && (u == nodes.size() || dist[k] < dist[u])) u = k;
    if (u == nodes.size()) break;
    done[u] = true;
    if (u == 1) break;
    for (std::size_t v = 0; v < nodes.size(); ++v) {
      if (done[v]) continue;
      const double nd = dist[u] + (nodes[v] - nodes[u]).norm();
      if (nd < dist[v] && grid::LineOfSight(map, nodes[u], nodes[v])) dist[v] = nd;
    }
  }
  return dist[1];
}

TEST(PropagationModel, MatchesABruteForceReferenceOnRandomMaps) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    grid::OccupancyMap map(16, 12, 0.5);
    // Random wall segments, horizontal and vertical.
    std::uniform_int_distribution<int> x(0, 15), y(0, 11), len(2, 8), dir(0, 1);
    for (int w = 0; w < 6; ++w) {
      const int x0 = x(rng), y0 = y(rng), l = len(rng);
      const bool horizontal = dir(rng);
      for (int k = 0; k < l; ++k) {
        const int i = horizontal ? x0 + k : x0, j = horizontal ? y0 : y0 + k;
        if (map.InBounds(i, j)) map.set(i, j, grid::Cell::kOccupied);
      }
    }
    for (auto rule : {DiffractionRule::kMasks, DiffractionRule::kConvexCorners}) {
      const PropagationModel model(map, Unlimited(rule));
      std::uniform_real_distribution<double> ux(0.0, 8.0), uy(0.0, 6.0);
      for (int q = 0; q < 8; ++q) {
        Eigen::Vector2d s, r;
        do s = {ux(rng), uy(rng)}; while (!map.IsFreeAt(s));
        do r = {ux(rng), uy(rng)}; while (!map.IsFreeAt(r));
        const double ref = BruteForce(map, s, r);
        const SoundPath p = model.Path(s, r);
        if (!std::isfinite(ref)) {
          EXPECT_FALSE(p.reachable);
          continue;
        }
        ASSERT_TRUE(p.reachable) << "trial " << trial << " " << s.transpose() << " -> " << r.transpose();
        EXPECT_GE(p.length, (r - s).norm() - 1e-9);
        EXPECT_NEAR(p.length, ref, map.resolution()) << DiffractionRuleName(rule) << " trial " << trial;
      }
    }
  }
}

// The memo reuses a cell's view of the corners for other points of the cell: the paths stay those
// of the exact computation to within a cell, and the first point asked about in a cell gets the
// exact path itself.
TEST(PropagationModel, FromThroughAMemoIsExactToWithinACell) {
  std::mt19937 rng(5);
  grid::OccupancyMap map(40, 30, 0.25);
  for (int j = 0; j < 22; ++j) map.set(13, j, grid::Cell::kOccupied);
  for (int j = 8; j < 30; ++j) map.set(27, j, grid::Cell::kOccupied);
  const PropagationModel model(map, Unlimited());
  std::uniform_real_distribution<double> ux(0.0, 10.0), uy(0.0, 7.5), jitter(0.0, 0.25);
  std::vector<Eigen::Vector2d> listeners;
  while (listeners.size() < 40) {
    const Eigen::Vector2d p(ux(rng), uy(rng));
    if (map.IsFreeAt(p)) listeners.push_back(p);
  }
  VisibilityMemo memo(1000);
  const Eigen::Vector2d source(1.0, 1.0);
  const std::vector<SoundPath> first = model.From(source, listeners, &memo);
  const std::vector<SoundPath> exact = model.From(source, listeners);
  for (std::size_t k = 0; k < listeners.size(); ++k) {
    ASSERT_EQ(first[k].reachable, exact[k].reachable) << k;
    EXPECT_DOUBLE_EQ(first[k].length, exact[k].length) << k;
  }
  const std::uint64_t misses = memo.misses();
  EXPECT_GT(misses, 0u);
  // The same cells again, from other points in them (and another source).
  std::vector<Eigen::Vector2d> moved;
  for (const Eigen::Vector2d& p : listeners) {
    const Eigen::Vector2d corner(std::floor(p.x() / 0.25) * 0.25, std::floor(p.y() / 0.25) * 0.25);
    Eigen::Vector2d q;
    do q = corner + Eigen::Vector2d(jitter(rng), jitter(rng)); while (!map.IsFreeAt(q));
    moved.push_back(q);
  }
  const Eigen::Vector2d other(9.0, 7.0);
  const std::vector<SoundPath> reused = model.From(other, moved, &memo);
  const std::vector<SoundPath> truth = model.From(other, moved);
  EXPECT_GT(memo.hits(), 0u);
  int blocked = 0;
  for (std::size_t k = 0; k < moved.size(); ++k) {
    ASSERT_EQ(reused[k].reachable, truth[k].reachable) << k;
    if (!truth[k].reachable) continue;
    blocked += truth[k].bends > 0;
    EXPECT_NEAR(reused[k].length, truth[k].length, 0.25 * std::sqrt(2.0)) << k;
    EXPECT_GE(reused[k].length, (moved[k] - other).norm() - 1e-9) << k;
  }
  EXPECT_GT(blocked, 5) << "too few listeners behind the walls to test the memo";
}

}  // namespace
}  // namespace audio_propagation
