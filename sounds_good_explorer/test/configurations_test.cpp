#include "sounds_good_explorer/configurations.h"

#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "grid/input_error.h"
#include "grid/map_file.h"
#include "world_sim/world_file.h"

namespace sounds_good_explorer {
namespace {

const std::string kOffice = std::string(PROJECT_MAPS_DIR) + "/office.yaml";

TEST(Configurations, RandomConfigurationsAreValidAndSpreadOut) {
  const grid::OccupancyMap map = grid::LoadMapFile(kOffice);
  std::mt19937 rng(4);
  const world_sim::RobotModel body;
  for (int k = 0; k < 10; ++k) {
    const world_sim::WorldConfig c = RandomConfiguration(map, kOffice, body, {}, rng);
    ASSERT_EQ(c.robots.size(), 5u);
    ASSERT_EQ(c.markers.size(), 2u);
    EXPECT_EQ(c.markers[0].id, 1u);
    EXPECT_EQ(c.markers[1].id, 2u);
    EXPECT_GE((Eigen::Vector2d(c.markers[0].x, c.markers[0].y) -
               Eigen::Vector2d(c.markers[1].x, c.markers[1].y)).norm(), 3.0);
    EXPECT_EQ(c.robots[4].name, "robot_4");
    EXPECT_NO_THROW(ValidateConfiguration("random", c, map, 1, 2)) << k;
  }
}

// A 6 x 6 m map with a closed 1 m box of walls around (4.5, 4.5).
grid::OccupancyMap BoxedMap() {
  grid::OccupancyMap map(60, 60, 0.1);
  for (int i = 0; i < 60; ++i)
    for (int j : {0, 59}) map.set(i, j, grid::Cell::kOccupied), map.set(j, i, grid::Cell::kOccupied);
  for (int i = 40; i <= 50; ++i)
    for (int j : {40, 50}) map.set(i, j, grid::Cell::kOccupied), map.set(j, i, grid::Cell::kOccupied);
  return map;
}

world_sim::WorldConfig TwoRobots() {
  world_sim::WorldConfig c;
  c.map_file = "boxed";
  c.robots = {{"a", {1.0, 1.0, 0.0}}, {"b", {2.0, 1.0, 0.0}}};
  c.markers = {{1, 3.0, 3.0}, {2, 1.0, 4.0}};
  return c;
}

void ExpectError(const world_sim::WorldConfig& c, const std::string& words) {
  try {
    ValidateConfiguration("w.yaml", c, BoxedMap(), 1, 2);
    FAIL() << "expected an error with '" << words << "'";
  } catch (const grid::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("w.yaml", 0), 0u) << e.what();
  }
}

TEST(Configurations, ValidationNamesWhatCannotBeReached) {
  EXPECT_NO_THROW(ValidateConfiguration("w.yaml", TwoRobots(), BoxedMap(), 1, 2));
  world_sim::WorldConfig c = TwoRobots();
  c.markers[1] = {2, 4.5, 4.5};  // inside the closed box
  ExpectError(c, "marker 2 at (4.5, 4.5) cannot be reached");
  c = TwoRobots();
  c.robots[1].start = {4.5, 4.4, 0.0};  // a robot shut in the box
  ExpectError(c, "robot 'b'");
  c = TwoRobots();
  c.robots[0].start = {0.05, 3.0, 0.0};  // in the outer wall
  ExpectError(c, "robots[0]");
  c = TwoRobots();
  c.markers.pop_back();
  ExpectError(c, "expected a marker with id 2 (the sink)");
  c = TwoRobots();
  c.robots.clear();
  ExpectError(c, "robots");
}

TEST(Configurations, ShippedSoundsGoodWorldsAreValid) {
  for (const char* name : {"sounds_good_world.yaml", "test_room_sounds_good_world.yaml"}) {
    const std::string file = std::string(PROJECT_MAPS_DIR) + "/" + name;
    const world_sim::LoadedWorld w = world_sim::LoadWorldFile(file);
    EXPECT_NO_THROW(ValidateConfiguration(file, w.config, w.map, 1, 2)) << name;
  }
}

TEST(Configurations, ImpossibleRequestsAreRefused) {
  const grid::OccupancyMap map = BoxedMap();
  std::mt19937 rng(1);
  ConfigurationOptions o;
  o.robots = 0;
  EXPECT_THROW(RandomConfiguration(map, "boxed", {}, o, rng), std::invalid_argument);
  o.robots = 2;
  o.min_marker_separation = 100.0;  // no two points of a 6 m map are that far apart
  EXPECT_THROW(RandomConfiguration(map, "boxed", {}, o, rng), std::invalid_argument);
  EXPECT_NO_THROW(ValidateOptions(ConfigurationOptions{}));
  o = {};
  o.sink = o.source;
  EXPECT_THROW(RandomConfiguration(map, "boxed", {}, o, rng), std::invalid_argument);
  o = {};
  o.margin = -0.5;
  try {
    ValidateOptions(o);
    ADD_FAILURE() << "a negative margin was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "configuration margin (m) must be >= 0, got -0.5");
  }
}

}  // namespace
}  // namespace sounds_good_explorer
