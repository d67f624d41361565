#pragma once

#include <vector>

#include <Eigen/Core>

#include "grid/occupancy_map.h"
#include "grid/pose2d.h"
#include "world_sim/world_config.h"

namespace world_sim {

// Angle of ranger k in the robot frame: spread evenly, ranger 0 facing ahead.
double IrAngle(const RobotModel& model, int k);

// Readings of the robot's IR rangers: distance from the robot's centre to the nearest wall or
// other robot along each ranger's beam, +inf when nothing is within the ranger's reach
// (model.radius + model.ir_range from the centre), as REP-117 asks.
std::vector<float> IrRanges(const grid::OccupancyMap& map, const RobotModel& model,
                            const grid::Pose2D& pose, const std::vector<Eigen::Vector2d>& others);

}  // namespace world_sim
