#include "world_sim/world.h"

#include <cmath>

#include <gtest/gtest.h>

#include "grid/input_error.h"
#include "behaviours/wanderer.h"
#include "world_sim/world_file.h"

namespace world_sim {
namespace {

// A 10 x 6 m room with a wall whose face is at x = 5.0.
grid::OccupancyMap Room() {
  grid::OccupancyMap map(200, 120, 0.05);
  for (int j = 0; j < 120; ++j)
    for (int i = 100; i < 103; ++i) map.set(i, j, grid::Cell::kOccupied);
  return map;
}

WorldConfig TwoRobots() {
  WorldConfig c;
  c.map_file = "room";
  c.robots = {{"a", {2.0, 3.0, 0.0}, Microphone::kOmni, 1.0},
              {"b", {3.0, 1.0, 0.0}, Microphone::kOmni, 1.0}};
  return c;
}

void RunFor(World& w, double seconds) {
  const int steps = static_cast<int>(std::lround(seconds / w.options().step));
  for (int k = 0; k < steps; ++k) w.Step();
}

TEST(World, ClockStartsAboveZeroAndAdvancesByTheStep) {
  World w(Room(), TwoRobots());
  EXPECT_GT(w.time(), 0.0);
  const double t0 = w.time();
  RunFor(w, 1.0);
  EXPECT_NEAR(w.time() - t0, 1.0, 1e-9);
  EXPECT_EQ(w.steps(), 50u);
}

TEST(World, RejectsImpossibleOptions) {
  WorldOptions o;
  o.step = 0.0;
  EXPECT_THROW(World(Room(), TwoRobots(), o), std::invalid_argument);
  o = {};
  o.scan_period = 0.001;
  EXPECT_THROW(World(Room(), TwoRobots(), o), std::invalid_argument);
  EXPECT_NO_THROW(ValidateOptions(WorldOptions{}));
  try {
    ValidateOptions(o);
    ADD_FAILURE() << "a scan period under the step was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "world_sim: scan_period must be >= step (0.020000 s), got 0.001000");
  }
  WorldConfig inside = TwoRobots();
  inside.robots[0].start = {5.05, 3.0, 0.0};
  EXPECT_THROW(World(Room(), inside), grid::InputError);
}

TEST(World, DrivesAtTheCommandedSpeedClampedToTheModel) {
  World w(Room(), TwoRobots());
  w.SetCommand(0, 1.0, 0.0);  // above the 0.3 m/s limit
  RunFor(w, 2.0);
  EXPECT_NEAR(w.robots()[0].pose.x, 2.6, 1e-9);
  EXPECT_NEAR(w.robots()[0].distance, 0.6, 1e-9);
  EXPECT_FALSE(w.robots()[0].stalled);
}

TEST(World, RobotDrivenAtAWallStopsBeforeItAndCountsOneCollision) {
  World w(Room(), TwoRobots());
  w.SetCommand(0, 0.3, 0.0);
  RunFor(w, 15.0);
  const RobotState& r = w.robots()[0];
  EXPECT_TRUE(r.stalled);
  EXPECT_EQ(r.collisions, 1);
  EXPECT_LE(r.pose.x, 5.0 - 0.075);
  EXPECT_GT(r.pose.x, 5.0 - 0.075 - 0.3 * w.options().step - 1e-9);
  // Its front ranger reads the gap to the wall from its centre.
  EXPECT_NEAR(r.scan[0], 5.0 - r.pose.x, 1e-5);
  // Backing off clears the stall and the count stays.
  w.SetCommand(0, -0.2, 0.0);
  RunFor(w, 1.0);
  EXPECT_FALSE(w.robots()[0].stalled);
  EXPECT_EQ(w.robots()[0].collisions, 1);
  EXPECT_EQ(w.TotalCollisions(), 1);
}

TEST(World, RobotsStopAgainstEachOther) {
  WorldConfig c = TwoRobots();
  c.robots[1].start = {3.0, 3.0, M_PI};
  World w(Room(), c);
  w.SetCommand(0, 0.3, 0.0);
  RunFor(w, 5.0);
  EXPECT_TRUE(w.robots()[0].stalled);
  EXPECT_GE((w.robots()[0].pose.position() - w.robots()[1].pose.position()).norm(), 0.15 - 1e-9);
  EXPECT_LT(w.robots()[0].pose.x, 3.0 - 0.15 + 1e-9);
  EXPECT_EQ(w.robots()[1].collisions, 0);  // b did not move
}

TEST(World, TurningAgainstAWallStillTurns) {
  WorldConfig c = TwoRobots();
  c.robots[0].start = {4.92, 3.0, 0.0};
  World w(Room(), c);
  w.SetCommand(0, 0.3, 1.0);
  w.Step();
  EXPECT_TRUE(w.robots()[0].stalled);
  EXPECT_NEAR(w.robots()[0].pose.yaw, 0.02, 1e-12);
}

TEST(World, OdometryDriftsButFollowsTheTruth) {
  World w(Room(), TwoRobots());
  w.SetCommand(0, 0.2, 0.1);
  RunFor(w, 10.0);
  const RobotState& r = w.robots()[0];
  // The odom frame starts at the robot's start pose.
  const grid::Pose2D truth_in_start = grid::Compose(grid::Inverse(TwoRobots().robots[0].start), r.pose);
  EXPECT_NEAR(r.odom.x, truth_in_start.x, 0.1);
  EXPECT_NEAR(r.odom.y, truth_in_start.y, 0.1);
  EXPECT_NE(r.odom.x, truth_in_start.x);  // but not exactly
}

TEST(World, BatteryDrainsAndChargesAtACharger) {
  WorldConfig c = TwoRobots();
  c.model.battery.idle_drain = 0.01;
  c.model.battery.charge_rate = 0.02;
  c.chargers = {{{3.0, 1.0, 0.0}, 0.2, 100u}};
  c.robots[0].battery = 0.5;
  World w(Room(), c);
  RunFor(w, 10.0);
  EXPECT_NEAR(w.robots()[0].battery, 0.4, 1e-6);  // away from chargers: drains
  EXPECT_TRUE(w.robots()[1].docked);
  EXPECT_NEAR(w.robots()[1].battery, 1.0, 1e-12);  // docked: charges (and stays full)
  EXPECT_EQ(w.fiducials().size(), 1u);  // the charger's marker
}

TEST(World, EmptyBatteryStopsTheRobot) {
  WorldConfig c = TwoRobots();
  c.robots[0].battery = 0.0;
  World w(Room(), c);
  w.SetCommand(0, 0.3, 0.0);
  RunFor(w, 1.0);
  EXPECT_DOUBLE_EQ(w.robots()[0].pose.x, 2.0);
}

TEST(World, SensorsRunAtTheirPeriods) {
  World w(Room(), TwoRobots());
  RunFor(w, 0.1);
  EXPECT_EQ(w.robots()[0].scan_step, 5u);
  EXPECT_EQ(w.robots()[0].fiducials_step, 0u);
  RunFor(w, 0.1);
  EXPECT_EQ(w.robots()[0].fiducials_step, 10u);
}

// Runs a wandering team for a while and returns every robot's trajectory.
std::vector<std::vector<grid::Pose2D>> Wander(std::uint32_t seed) {
  const LoadedWorld loaded = LoadWorldFile(std::string(PROJECT_MAPS_DIR) + "/office_world.yaml");
  WorldConfig config = loaded.config;
  config.seed = seed;
  World w(loaded.map, config);
  std::vector<behaviours::Wanderer> brains;
  for (std::size_t k = 0; k < w.robots().size(); ++k) brains.emplace_back(behaviours::WanderOptions{}, seed + k);
  std::vector<std::vector<grid::Pose2D>> paths(w.robots().size());
  for (int step = 0; step < 3000; ++step) {
    for (std::size_t k = 0; k < w.robots().size(); ++k) {
      const behaviours::VelocityCommand cmd = brains[k].Update(w.robots()[k].scan, w.options().step);
      w.SetCommand(k, cmd.v, cmd.w);
      paths[k].push_back(w.robots()[k].odom);
    }
    w.Step();
  }
  return paths;
}

TEST(World, SameSeedSameTrajectories) {
  const auto a = Wander(5), b = Wander(5), c = Wander(6);
  bool any_difference = false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t s = 0; s < a[k].size(); ++s) {
      ASSERT_EQ(a[k][s].x, b[k][s].x);
      ASSERT_EQ(a[k][s].y, b[k][s].y);
      ASSERT_EQ(a[k][s].yaw, b[k][s].yaw);
      any_difference = any_difference || a[k][s].x != c[k][s].x;
    }
  }
  EXPECT_TRUE(any_difference) << "a different seed should give different odometry";
}

}  // namespace
}  // namespace world_sim
