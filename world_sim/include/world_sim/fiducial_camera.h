#pragma once

#include <cstdint>
#include <vector>

#include "grid/occupancy_map.h"
#include "grid/pose2d.h"
#include "world_sim/world_config.h"

namespace world_sim {

struct FiducialSighting {
  std::uint32_t id = 0;
  double range = 0.0;    // m from the robot's centre
  double bearing = 0.0;  // rad in the robot frame, CCW from ahead
};

// The markers the robot's camera sees: within camera_range, inside the field of view, with a
// clear line of sight past the walls (robots do not hide markers). Nearest first.
std::vector<FiducialSighting> SeeFiducials(const grid::OccupancyMap& map, const RobotModel& model,
                                           const grid::Pose2D& pose,
                                           const std::vector<MarkerSpec>& markers);

}  // namespace world_sim
