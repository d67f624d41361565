#pragma once

#include "grid/pose2d.h"

namespace world_sim {

// Pose after driving a unicycle at forward speed v (m/s) and turn rate w (rad/s) for dt seconds,
// integrated exactly along the arc.
grid::Pose2D IntegrateUnicycle(const grid::Pose2D& pose, double v, double w, double dt);

}  // namespace world_sim
