#pragma once

#include <vector>

#include <Eigen/Core>

#include "grid/pose2d.h"
#include "local_navigation/local_navigator.h"

namespace charging_demo {

// Range readings as the robot would see them if every disc of `radius` around `centres` (odom
// frame) were a wall: each reading is cut to where its ray enters a disc. Inside a disc, rays
// that point into it read 0 and the others see out as before, so a reactive behaviour turns
// out of it. This keeps wandering robots off chargers they are not docking at, with no change
// to the behaviour itself. Pure; `readings` bearings are in the robot frame.
std::vector<local_navigation::RangeReading> KeepOutRanges(
    const std::vector<local_navigation::RangeReading>& readings, const grid::Pose2D& pose,
    const std::vector<Eigen::Vector2d>& centres, double radius);

}  // namespace charging_demo
