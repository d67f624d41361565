#pragma once

// The test room with acoustics (maps/test_room_acoustic_world.yaml), its propagation model with
// every path, as the validation tools build it, and its robots' names and places.
#include <string>
#include <vector>

#include "audio_propagation/channel_validation.h"
#include "world_sim/world_file.h"

namespace audio_propagation::test {

struct TestRoom {
  world_sim::LoadedWorld world =
      world_sim::LoadWorldFile(std::string(MULTIROBOT_AUDIO_MAPS_DIR) + "/test_room_acoustic_world.yaml");
  PropagationModel propagation{world.map, ValidationPropagation(world.map.width_m() + world.map.height_m(), 1)};
  std::vector<std::string> names;
  std::vector<Eigen::Vector2d> resting;
  TestRoom() {
    for (const world_sim::RobotSpec& r : world.config.robots) names.push_back(r.name), resting.push_back(r.start.position());
  }
};

}  // namespace audio_propagation::test
