// Going back along the trail: a robot that saw a charger in a corridor and then went into a room
// finds its way back to it through the door, which its local map forgot long ago.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "charging_demo/charging_controller.h"
#include "local_navigation/world_readings.h"
#include "world_sim/world.h"

namespace charging_demo {
namespace {

constexpr std::uint32_t kMarker = 100;

// 12 m x 8 m: a corridor along the bottom (y < 2), a room above it, and the only door between
// them at x = 10..11 m.
grid::OccupancyMap CorridorAndRoom() {
  grid::OccupancyMap map(240, 160, 0.05);
  for (int i = 0; i < map.width(); ++i) {
    const double x = map.CellCenter(i, 0).x();
    if (x > 10.0 && x < 11.0) continue;
    for (int j = 40; j < 42; ++j) map.set(i, j, grid::Cell::kOccupied);
  }
  return map;
}

world_sim::WorldConfig OneRobotOneCharger() {
  world_sim::WorldConfig config;
  config.robots.push_back({"robot_0", grid::Pose2D{6.0, 1.0, M_PI}, world_sim::Microphone::kNone, 1.0});
  world_sim::ChargerSpec charger;
  charger.pose = grid::Pose2D{3.0, 1.0, 0.0};
  charger.marker = kMarker;
  config.chargers.push_back(charger);
  return config;
}

// Steers the robot through `waypoints` in the map frame; true once past the last.
bool Drive(world_sim::World& world, std::vector<Eigen::Vector2d>& waypoints) {
  const grid::Pose2D& pose = world.robots()[0].pose;
  while (!waypoints.empty() && (waypoints.front() - pose.position()).norm() < 0.15) waypoints.erase(waypoints.begin());
  if (waypoints.empty()) {
    world.SetCommand(0, 0.0, 0.0);
    return true;
  }
  const Eigen::Vector2d to = waypoints.front() - pose.position();
  const double error = grid::NormalizeAngle(std::atan2(to.y(), to.x()) - pose.yaw);
  world.SetCommand(0, std::abs(error) < 0.3 ? 0.3 : 0.0, std::clamp(3.0 * error, -2.0, 2.0));
  return false;
}

struct Outcome {
  Phase phase = Phase::kDuty;  // `limit` s after the battery went low, or on docking
  double seconds = 0.0;        // from the battery going low to docking (or `limit`)
  std::uint64_t retraces = 0;
};

// Runs the scenario until the robot docks or `limit` s after its battery went low.
Outcome GoBackToTheCharger(const ControllerOptions& options, double limit) {
  world_sim::World world(CorridorAndRoom(), OneRobotOneCharger());
  ChargingController robot(options);
  local_navigation::WorldReadings readings(world.config().model, 1);
  // Seen from the corridor, then out of the door and along the room to the spot just above
  // the charger: 3 m away through the wall, the door 7.5 m behind.
  std::vector<Eigen::Vector2d> route = {{10.5, 1.0}, {10.5, 3.5}, {3.0, 3.5}};
  bool low = false, held = false;
  double low_since = 0.0;
  const double period = 0.1;
  double next = 0.0;
  while (!low || world.elapsed() - low_since < limit) {
    world.Step();
    if (world.elapsed() < next) continue;
    next += period;
    const double now = world.elapsed();
    const world_sim::RobotState& s = world.robots()[0];
    const local_navigation::WorldReadings::Fresh fresh = readings.Take(0, s);
    if (fresh.odom) robot.OnOdometry(s.odom, now);
    if (fresh.ranges) robot.OnRanges(readings.ranges(), readings.reach(), now);
    if (fresh.fiducials) {
      std::vector<ChargerSighting> sightings;
      for (const world_sim::FiducialSighting& f : s.fiducials) sightings.push_back({f.id, f.range, f.bearing});
      robot.OnSightings(sightings);
    }
    // Full while it is driven into the room, low from then on; the lock is granted at once.
    robot.OnBattery(low ? 0.2 : 1.0, s.docked);
    const ControllerOutput out = robot.Update(held ? local_mutex::State::kHeld : local_mutex::State::kReleased, now);
    held = out.want_lock;
    if (!low) {
      if (Drive(world, route)) {
        low = true;
        low_since = now;
      }
      continue;
    }
    world.SetCommand(0, out.v, out.w);
    if (robot.behaviour().phase() == Phase::kCharge) break;
  }
  return {robot.behaviour().phase(), world.elapsed() - low_since, robot.retraces()};
}

ControllerOptions Options() {
  ControllerOptions o;
  o.charging.chargers = {kMarker};
  return o;
}

// Straight towards the charger ends against the wall: the robot goes back along the trail to
// the corridor. Never going back, it feels its way along the wall through space its local map
// does not know, and gets there later.
TEST(Retrace, FindsTheWayBackToAChargerBehindAWall) {
  const Outcome back = GoBackToTheCharger(Options(), 300.0);
  EXPECT_EQ(back.phase, Phase::kCharge);
  EXPECT_GE(back.retraces, 1u);
  ControllerOptions direct = Options();
  direct.charging.approach_timeout = 2e9;
  direct.retrace_after = 1e9;
  const Outcome straight = GoBackToTheCharger(direct, 300.0);
  EXPECT_EQ(straight.retraces, 0u);
  EXPECT_LT(back.seconds, straight.seconds);
  std::printf("docked %.0f s after going low going back along the trail, %.0f s without\n", back.seconds,
              straight.seconds);
}

}  // namespace
}  // namespace charging_demo
