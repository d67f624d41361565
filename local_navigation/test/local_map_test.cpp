#include "local_navigation/local_map.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

namespace local_navigation {
namespace {

// 11 x 11 cells of 1 m: easy to count by hand. The map is centred on the origin, so cell
// (5, 5) holds [0, 1) x [0, 1) once recentred on (0.5, 0.5).
LocalMap SmallMap(double expiry = 10.0) {
  LocalMap map(LocalMapOptions{11, 1.0, expiry, 0.0});  // sweep at every call
  map.Recentre({0.5, 0.5});
  return map;
}

TEST(LocalMap, BeamMarksFreeCellsAndTheCellItEndsIn) {
  LocalMap map = SmallMap();
  // From the centre of cell (5, 5) east: 3.2 m hits something in cell (8, 5).
  map.AddRange({0.5, 0.5, 0.0}, 0.0, 3.2, 4.0, 1.0);
  EXPECT_EQ(map.at({5, 5}), CellState::kFree);
  EXPECT_EQ(map.at({6, 5}), CellState::kFree);
  EXPECT_EQ(map.at({7, 5}), CellState::kFree);
  EXPECT_EQ(map.at({8, 5}), CellState::kOccupied);
  EXPECT_EQ(map.at({9, 5}), CellState::kUnknown);
  EXPECT_EQ(map.at({5, 6}), CellState::kUnknown);
  EXPECT_EQ(map.at({4, 5}), CellState::kUnknown);
}

TEST(LocalMap, NothingInReachMarksTheWholeBeamFree) {
  LocalMap map = SmallMap();
  const double inf = std::numeric_limits<double>::infinity();
  // North, rotated robot: bearing -pi/2 from a robot facing pi.
  map.AddRange({0.5, 0.5, M_PI}, -M_PI / 2, inf, 3.0, 1.0);
  for (int y = 5; y <= 8; ++y) EXPECT_EQ(map.at({5, y}), CellState::kFree) << y;
  EXPECT_EQ(map.at({5, 9}), CellState::kUnknown);
  map.AddRange({0.5, 0.5, 0.0}, M_PI, std::nan(""), 2.0, 1.0);
  EXPECT_EQ(map.at({3, 5}), CellState::kFree);
  EXPECT_EQ(map.at({2, 5}), CellState::kUnknown);
}

TEST(LocalMap, ASectorClearsItsShareOfTheRingButKeepsObstacles) {
  LocalMap map = SmallMap();
  map.Set({8, 6}, CellState::kOccupied, 0.5);  // seen before, off the beam's axis
  // East, +-pi/8, nothing within 4 m. Offsets (3, +-1) are 18.4 degrees off the axis and
  // 3.16 m away: inside the sector; (2, 1) is 26.6 degrees off: outside.
  map.AddRange({0.5, 0.5, 0.0}, 0.0, std::numeric_limits<double>::infinity(), 4.0, 1.0, M_PI / 8);
  for (int x = 5; x <= 9; ++x) EXPECT_EQ(map.at({x, 5}), CellState::kFree) << x;
  EXPECT_EQ(map.at({8, 4}), CellState::kFree);
  EXPECT_EQ(map.at({8, 6}), CellState::kOccupied);  // inside, but known occupied
  EXPECT_EQ(map.at({7, 6}), CellState::kUnknown);   // another beam's share
  EXPECT_EQ(map.at({7, 7}), CellState::kUnknown);
  EXPECT_EQ(map.at({4, 5}), CellState::kUnknown);   // behind
  // West, across the +-pi seam, hitting something at 2.2 m: cleared to half a cell short.
  map.AddRange({0.5, 0.5, 0.0}, M_PI, 2.2, 4.0, 2.0, M_PI / 8);
  EXPECT_EQ(map.at({4, 5}), CellState::kFree);
  EXPECT_EQ(map.at({3, 5}), CellState::kOccupied);
  EXPECT_EQ(map.at({3, 4}), CellState::kUnknown);  // 26.6 degrees off the axis
  EXPECT_EQ(map.at({4, 4}), CellState::kUnknown);  // 45 degrees off
}

TEST(LocalMap, CellsExpireBackToUnknown) {
  LocalMap map = SmallMap(10.0);
  map.Set({1, 1}, CellState::kOccupied, 1.0);
  map.Set({2, 2}, CellState::kFree, 6.0);
  map.Expire(11.0);
  EXPECT_EQ(map.at({1, 1}), CellState::kOccupied);  // exactly the expiry: still known
  map.Expire(11.5);
  EXPECT_EQ(map.at({1, 1}), CellState::kUnknown);
  EXPECT_EQ(map.at({2, 2}), CellState::kFree);
  map.Expire(16.5);
  EXPECT_EQ(map.at({2, 2}), CellState::kUnknown);
}

TEST(LocalMap, ExpirySweepsAtMostOncePerStep) {
  LocalMap map(LocalMapOptions{11, 1.0, 10.0, 1.0});
  map.Set({1, 1}, CellState::kFree, 1.0);
  map.Expire(10.8);  // sweeps: nothing old enough yet
  map.Expire(11.5);  // within a second of the last sweep: skipped
  EXPECT_EQ(map.at({1, 1}), CellState::kFree);
  map.Expire(11.8);
  EXPECT_EQ(map.at({1, 1}), CellState::kUnknown);
  EXPECT_THROW(LocalMap(LocalMapOptions{11, 1.0, 10.0, -1.0}), std::invalid_argument);
  // A step longer than the expiry sweeps once per expiry.
  LocalMap slow(LocalMapOptions{11, 1.0, 2.0, 60.0});
  slow.Set({1, 1}, CellState::kFree, 1.0);
  slow.Expire(2.0);
  slow.Expire(4.5);
  EXPECT_EQ(slow.at({1, 1}), CellState::kUnknown);
  // Wall-clock stamps keep their sub-second resolution.
  LocalMap wall(LocalMapOptions{11, 1.0, 20.0, 0.0});
  wall.Set({1, 1}, CellState::kFree, 1.7e9);
  wall.Expire(1.7e9 + 19.9);
  EXPECT_EQ(wall.at({1, 1}), CellState::kFree);
  wall.Expire(1.7e9 + 20.1);
  EXPECT_EQ(wall.at({1, 1}), CellState::kUnknown);
}

TEST(LocalMap, RecentringKeepsCellsWhereTheyAreInOdomAndDropsThoseThatFallOff) {
  LocalMap map = SmallMap();
  map.Set({0, 5}, CellState::kOccupied, 1.0);  // odom [-5, -4) x [0, 1)
  map.Set({7, 6}, CellState::kFree, 1.0);      // odom [2, 3) x [1, 2)
  const Eigen::Vector2d occupied = map.CentreOf({0, 5}), free = map.CentreOf({7, 6});
  map.Recentre({2.4, 0.9});  // two cells east
  EXPECT_EQ(map.centre_cell(), map.CellOf({2.4, 0.9}));
  EXPECT_EQ(map.at(map.CellOf(free)), CellState::kFree);
  EXPECT_EQ(map.CellOf(free), Eigen::Vector2i(5, 6));
  EXPECT_FALSE(map.Inside(map.CellOf(occupied)));  // fell off the west edge
  map.Recentre({0.5, 0.5});  // back: the lost cell does not come back
  EXPECT_EQ(map.at({0, 5}), CellState::kUnknown);
  EXPECT_EQ(map.at({7, 6}), CellState::kFree);
}

TEST(LocalMap, RejectsImpossibleOptions) {
  EXPECT_THROW(LocalMap(LocalMapOptions{10, 0.15, 20.0}), std::invalid_argument);
  EXPECT_THROW(LocalMap(LocalMapOptions{11, 0.0, 20.0}), std::invalid_argument);
  EXPECT_THROW(LocalMap(LocalMapOptions{11, 0.15, -1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace local_navigation
