#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "grid/occupancy_map.h"
#include "world_sim/world_config.h"

namespace charging_demo {

struct ChargingWorldOptions {
  int robots = 4;
  int chargers = 1;
  std::uint32_t first_marker = 100;  // chargers carry fiducials first_marker, first_marker + 1, ...
  double charger_clearance = 0.5;    // m from every wall: a robot can reach it from any side
  // m between chargers: beyond the hearing range, chargers are independent (one lock each);
  // within it, one lock serialises them (safe, slower).
  double charger_spacing = 12.0;
  double robot_clearance = 1.5;      // m from every charger at the start
  double margin = 0.05;              // m of room beyond the robot's radius at every start
  double min_battery = 0.4;          // initial levels are drawn from [min_battery, 1]
};

// Throws std::invalid_argument naming the field, its value and what was expected: chargers at
// least 1, robots within 1..255 (the lock's ids), min_battery within (0, 1], clearances,
// spacing and margin at least 0.
void ValidateOptions(const ChargingWorldOptions& options);

// A random world for the charging trial: `chargers` chargers in free space with room around
// them, pairwise `charger_spacing` apart, and `robots` robots (robot_0 ...) with random poses
// and battery levels, all in the map's largest connected free region, none overlapping.
// Throws std::invalid_argument for impossible options (ValidateOptions) or naming what does not
// fit (more robots or chargers than the map holds) after a bounded number of draws.
world_sim::WorldConfig RandomChargingWorld(const grid::OccupancyMap& map, const std::string& map_file,
                                           const world_sim::RobotModel& model,
                                           const ChargingWorldOptions& options, std::mt19937& rng);

// Checks a world for the charging trial: at least one charger, every charger with a marker
// (the robots find chargers by sight), at least one robot, at most 255 (the lock's ids). Throws
// grid::InputError naming `file` and the field.
void ValidateChargingWorld(const std::string& file, const world_sim::WorldConfig& config);

}  // namespace charging_demo
