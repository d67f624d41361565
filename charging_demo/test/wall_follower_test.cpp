// Following walls in world_sim's office: out of a room, along the corridor and through the rooms
// on one side of it.
#include "charging_demo/wall_follower.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "grid/map_file.h"
#include "local_navigation/world_readings.h"
#include "world_sim/world.h"

namespace charging_demo {
namespace {

// Drives a follower from `start` in the office for `seconds`; returns the furthest x reached.
double FurthestEast(Hand hand, const grid::Pose2D& start, double seconds) {
  world_sim::WorldConfig config;
  config.robots.push_back({"robot_0", start, world_sim::Microphone::kNone, 1.0});
  world_sim::World world(grid::LoadMapFile(MULTIROBOT_AUDIO_MAPS_DIR "/office.yaml"), config);
  local_navigation::WorldReadings readings(world.config().model, 1);
  WallFollower follower({}, hand);
  double east = start.x;
  double next = 0.0;
  while (world.elapsed() < seconds) {
    world.Step();
    if (world.elapsed() < next) continue;
    next += 0.1;
    const world_sim::RobotState& s = world.robots()[0];
    if (readings.Take(0, s).ranges) {
      const local_navigation::Velocity v = follower.Update(readings.ranges(), 0.1);
      world.SetCommand(0, v.v, v.w);
    }
    east = std::max(east, s.pose.x);
  }
  return east;
}

// From the bottom-left room, in 15 minutes either hand gets past the middle of the 34 m building
// (both in fact go round all of it). A wanderer started there stays near the west end for long.
TEST(WallFollower, LeavesTheRoomAndWorksAlongTheCorridor) {
  for (const Hand hand : {Hand::kLeft, Hand::kRight}) {
    EXPECT_GT(FurthestEast(hand, {3.0, 2.5, 0.0}, 900.0), 15.0) << (hand == Hand::kLeft ? "left" : "right");
  }
}

}  // namespace
}  // namespace charging_demo
