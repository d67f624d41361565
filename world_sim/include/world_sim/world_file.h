#pragma once

#include <string>

#include "grid/occupancy_map.h"
#include "world_sim/world_config.h"

namespace world_sim {

struct LoadedWorld {
  WorldConfig config;
  grid::OccupancyMap map;
};

// Reads a world file (YAML):
//
//   map: office.yaml              # map_server YAML, relative to this file (or absolute)
//   seed: 1                       # optional
//   robot_model: {radius: 0.075, max_speed: 0.3, ...}   # optional, any subset of RobotModel
//   robots:   [{name: robot_0, pose: [x, y, yaw], microphone: omni, battery: 1.0}, ...]
//   markers:  [{id: 1, position: [x, y]}, ...]
//   chargers: [{pose: [x, y, yaw], radius: 0.2, marker: 100}, ...]
//   acoustics: {...}              # optional, for the acoustic channel model (acoustics.h); a
//                                 # noise source of kind recording names its audio file
//                                 # (`file:`, relative to this file or absolute), which must exist
//
// `map_override`, when not empty, replaces the file's map. The map's path is kept canonical
// (grid::CanonicalPath), so worlds that name one map through different links compare equal.
// Validates everything a simulation
// relies on (robots and markers in free space, unique names, sane model values) and throws
// grid::InputError naming the file and field otherwise.
LoadedWorld LoadWorldFile(const std::string& path, const std::string& map_override = "");

// Writes `config` as a world file that LoadWorldFile reads back to the same config (the map
// path made canonical, the whole robot model, every robot, marker and charger). Throws
// std::runtime_error naming the path when it cannot be written.
void SaveWorldFile(const std::string& path, const WorldConfig& config);

// Checks a config against its map; throws grid::InputError (`file` names the source).
void ValidateWorld(const std::string& file, const WorldConfig& config, const grid::OccupancyMap& map);

}  // namespace world_sim
