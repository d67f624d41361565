#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "grid/occupancy_map.h"
#include "world_sim/world_config.h"

namespace sounds_good_explorer {

struct ConfigurationOptions {
  int robots = 5;
  std::uint32_t source = 1;
  std::uint32_t sink = 2;
  double margin = 0.05;                 // m of room beyond the robot's radius at every start and marker
  double min_marker_separation = 3.0;   // m between source and sink
};

// Throws std::invalid_argument naming the field, its value and what was expected: robots under
// 1, the source and sink one marker, a negative margin or marker separation.
void ValidateOptions(const ConfigurationOptions& options);

// A valid starting configuration of the thesis (section 3.4): robots (robot_0 ...) with random
// poses and the source and sink markers, all in free space with room for a robot, nobody
// overlapping, and every marker reachable by every robot. The map file is recorded as given.
// Throws std::invalid_argument for impossible options (ValidateOptions) or when the map has
// no room for them after a bounded number of draws.
world_sim::WorldConfig RandomConfiguration(const grid::OccupancyMap& map,
                                           const std::string& map_file,
                                           const world_sim::RobotModel& model,
                                           const ConfigurationOptions& options, std::mt19937& rng);

// Checks a given configuration for a Sounds Good trial: the source and sink markers exist and
// every robot can reach both. Throws grid::InputError naming `file` and the robot or marker.
void ValidateConfiguration(const std::string& file, const world_sim::WorldConfig& config,
                           const grid::OccupancyMap& map, std::uint32_t source, std::uint32_t sink);

}  // namespace sounds_good_explorer
