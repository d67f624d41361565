#include "charging_demo/charging_trial.h"

#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "charging_demo/charging_world.h"
#include "grid/input_error.h"
#include "grid/map_file.h"

namespace charging_demo {
namespace {

const std::string kTestRoom = MULTIROBOT_AUDIO_MAPS_DIR "/test_room.yaml";

world_sim::WorldConfig RoomWorld(int robots, int chargers, std::uint32_t seed,
                                 const grid::OccupancyMap& map) {
  ChargingWorldOptions o;
  o.robots = robots;
  o.chargers = chargers;
  std::mt19937 rng(seed);
  return RandomChargingWorld(map, kTestRoom, world_sim::RobotModel{}, o, rng);
}

// The in-process check: four robots share one charger for two simulated hours.
TEST(ChargingTrial, FourRobotsShareOneChargerForTwoHours) {
  const grid::OccupancyMap map = grid::LoadMapFile(kTestRoom);
  const audio_propagation::PropagationModel model(map, {});
  for (std::uint32_t seed : {1u, 2u}) {
    const world_sim::WorldConfig world = RoomWorld(4, 1, seed, map);
    ChargingTrialOptions o;
    o.duration = 2.0 * 3600.0;
    o.seed = seed;
    const ChargingTrialResult r = RunChargingTrial(map, world, model, o);
    EXPECT_EQ(r.double_dockings, 0u) << "seed " << seed;
    EXPECT_EQ(r.flat_robots(), 0u) << "seed " << seed;
    for (std::size_t k = 0; k < r.robots.size(); ++k) {
      const RobotRecord& robot = r.robots[k];
      EXPECT_GE(robot.charges, 1u) << "seed " << seed << " robot " << k;
      EXPECT_EQ(robot.waits.size(), robot.charges) << "a wait is recorded per charge";
      EXPECT_GT(robot.lock.grants, 0u);
      EXPECT_GE(robot.min_battery, 0.05);
      // The record covers the whole trial, phase after phase.
      ASSERT_FALSE(robot.phases.empty());
      EXPECT_DOUBLE_EQ(robot.phases.front().start, 0.0);
      EXPECT_NEAR(robot.phases.back().end, o.duration, 1e-6);
      for (std::size_t i = 1; i < robot.phases.size(); ++i)
        EXPECT_DOUBLE_EQ(robot.phases[i].start, robot.phases[i - 1].end);
    }
    // More demand than one charger at once: someone queued, and the charger was busy a good
    // share of the time (a 10-minute charge per robot per hour or so).
    EXPECT_GT(r.mean_wait(), 40.0) << "the lock takes at least t_grab";
    EXPECT_GT(r.utilisation(), 0.2);
    EXPECT_LT(r.utilisation(), 1.0);
    EXPECT_GT(r.packets_sent, 0u);
    EXPECT_EQ(r.queue_overflows, 0u);
  }
}

TEST(ChargingTrial, SameSeedSameTrial) {
  const grid::OccupancyMap map = grid::LoadMapFile(kTestRoom);
  const audio_propagation::PropagationModel model(map, {});
  const world_sim::WorldConfig world = RoomWorld(3, 1, 5, map);
  ChargingTrialOptions o;
  o.duration = 1800.0;
  const ChargingTrialResult a = RunChargingTrial(map, world, model, o);
  const ChargingTrialResult b = RunChargingTrial(map, world, model, o);
  ASSERT_EQ(a.robots.size(), b.robots.size());
  EXPECT_EQ(a.charges(), b.charges());
  EXPECT_EQ(a.packets_sent, b.packets_sent);
  for (std::size_t k = 0; k < a.robots.size(); ++k) {
    ASSERT_EQ(a.robots[k].phases.size(), b.robots[k].phases.size());
    EXPECT_EQ(a.robots[k].battery, b.robots[k].battery);
  }
}

TEST(ChargingTrial, RefusesWorldsItCannotRun) {
  const grid::OccupancyMap map = grid::LoadMapFile(kTestRoom);
  const audio_propagation::PropagationModel model(map, {});
  world_sim::WorldConfig world = RoomWorld(2, 1, 3, map);
  world.chargers.clear();
  try {
    RunChargingTrial(map, world, model, {});
    FAIL() << "a world with no charger ran";
  } catch (const grid::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("chargers"), std::string::npos) << e.what();
  }
  world = RoomWorld(2, 1, 3, map);
  world.chargers[0].marker.reset();
  EXPECT_THROW(RunChargingTrial(map, world, model, {}), grid::InputError);
  ChargingTrialOptions o;
  o.controller.charging.low_battery = 1.5;
  EXPECT_THROW(RunChargingTrial(map, RoomWorld(2, 1, 3, map), model, o), std::invalid_argument);
}

TEST(ChargingWorld, RandomWorldsFitAndSayWhatDoesNot) {
  const grid::OccupancyMap map = grid::LoadMapFile(kTestRoom);
  const world_sim::WorldConfig world = RoomWorld(5, 1, 9, map);
  ASSERT_EQ(world.robots.size(), 5u);
  ASSERT_EQ(world.chargers.size(), 1u);
  EXPECT_EQ(*world.chargers[0].marker, 100u);
  for (const world_sim::RobotSpec& r : world.robots) {
    EXPECT_TRUE(map.IsFreeAt(r.start.position()));
    EXPECT_GE((r.start.position() - world.chargers[0].pose.position()).norm(), 1.5);
    EXPECT_GE(r.battery, 0.4);
    EXPECT_LE(r.battery, 1.0);
  }
  // The 6 x 4 m room has no two points 12 m apart, and no room for a crowd.
  try {
    RoomWorld(2, 2, 1, map);
    FAIL() << "two chargers 12 m apart fitted in a 6 x 4 m room";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cannot place 2 chargers"), std::string::npos) << e.what();
  }
  try {
    RoomWorld(255, 1, 1, map);
    FAIL() << "255 robots fitted in a 6 x 4 m room";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cannot fit 255 robots"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RoomWorld(0, 1, 1, map), std::invalid_argument);
  EXPECT_THROW(RoomWorld(2, 0, 1, map), std::invalid_argument);
}

TEST(ChargingWorld, ImpossibleOptionsAreNamed) {
  const auto message = [](void (*change)(ChargingWorldOptions&)) {
    ChargingWorldOptions o;
    change(o);
    try {
      ValidateOptions(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NO_THROW(ValidateOptions(ChargingWorldOptions{}));
  EXPECT_EQ(message([](ChargingWorldOptions& o) { o.robots = 256; }), "robots must be within 1..255, got 256");
  EXPECT_EQ(message([](ChargingWorldOptions& o) { o.charger_clearance = -1.0; }),
            "charger_clearance (m) must be >= 0, got -1");
  EXPECT_NE(message([](ChargingWorldOptions& o) { o.min_battery = 1.5; }).find("within (0, 1], got 1.5"),
            std::string::npos);
}

}  // namespace
}  // namespace charging_demo
