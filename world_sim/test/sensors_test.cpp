#include <cmath>

#include <gtest/gtest.h>

#include "world_sim/fiducial_camera.h"
#include "world_sim/ir_rangers.h"

namespace world_sim {
namespace {

// 10 x 10 m, 0.05 m cells, a wall whose face is at x = 5.0 running from y = 0 to y = 6, so
// there is a 4 m wide opening above it.
grid::OccupancyMap WallMap() {
  grid::OccupancyMap map(200, 200, 0.05);
  for (int j = 0; j < 120; ++j)
    for (int i = 100; i < 103; ++i) map.set(i, j, grid::Cell::kOccupied);
  return map;
}

TEST(IrRangers, ReadTheDistanceToAKnownWall) {
  const grid::OccupancyMap map = WallMap();
  const RobotModel model;
  const std::vector<float> r = IrRanges(map, model, {4.0, 3.0, 0.0}, {});
  ASSERT_EQ(r.size(), 8u);
  EXPECT_NEAR(r[0], 1.0, 1e-6);  // ahead, straight at the face
  EXPECT_NEAR(r[1], std::sqrt(2.0), 1e-6);  // 45 degrees left
  EXPECT_TRUE(std::isinf(r[4]));  // behind: 4 m of open floor, beyond reach
  EXPECT_TRUE(std::isinf(r[2]));
}

TEST(IrRangers, OutOfReachIsInfinity) {
  const grid::OccupancyMap map = WallMap();
  const RobotModel model;  // reach = 0.075 + 1.5 m
  EXPECT_NEAR(IrRanges(map, model, {5.0 - 1.57, 3.0, 0.0}, {})[0], 1.57, 1e-6);
  EXPECT_TRUE(std::isinf(IrRanges(map, model, {5.0 - 1.58, 3.0, 0.0}, {})[0]));
}

TEST(IrRangers, SeeOtherRobots) {
  const grid::OccupancyMap map = WallMap();
  const RobotModel model;
  const std::vector<float> r = IrRanges(map, model, {2.0, 3.0, M_PI / 2}, {{2.0, 3.5}});
  EXPECT_NEAR(r[0], 0.5 - model.radius, 1e-6);
}

TEST(FiducialCamera, SeesThroughADoorwayNotThroughAWall) {
  const grid::OccupancyMap map = WallMap();
  const RobotModel model;
  const std::vector<MarkerSpec> markers = {{1, 6.0, 3.0},   // behind the wall
                                           {2, 6.0, 8.0},   // through the opening
                                           {3, 1.0, 3.0}};  // in the open, behind the robot
  const auto seen = SeeFiducials(map, model, {4.0, 6.5, 0.0}, markers);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].id, 2u);
  EXPECT_NEAR(seen[0].range, std::hypot(2.0, 1.5), 1e-9);
  EXPECT_NEAR(seen[0].bearing, std::atan2(1.5, 2.0), 1e-9);
  EXPECT_EQ(seen[1].id, 3u);
  // From lower down, the wall is between the robot and marker 1.
  const auto low = SeeFiducials(map, model, {4.0, 3.0, 0.0}, markers);
  for (const auto& s : low) EXPECT_NE(s.id, 1u);
}

TEST(FiducialCamera, RangeAndFieldOfView) {
  const grid::OccupancyMap map = WallMap();
  RobotModel model;
  model.camera_fov = M_PI / 2;
  const std::vector<MarkerSpec> markers = {{1, 2.8, 8.0}, {2, 2.0, 9.9}, {3, 1.0, 7.0}};
  const auto seen = SeeFiducials(map, model, {2.0, 7.0, M_PI / 2}, markers);
  ASSERT_EQ(seen.size(), 2u);  // marker 3 is 90 degrees to the left, outside a 90 degree view
  EXPECT_EQ(seen[0].id, 1u);
  EXPECT_EQ(seen[1].id, 2u);
  model.camera_range = 2.0;
  const auto near = SeeFiducials(map, model, {2.0, 7.0, M_PI / 2}, markers);
  ASSERT_EQ(near.size(), 1u);
  EXPECT_EQ(near[0].id, 1u);
}

}  // namespace
}  // namespace world_sim
