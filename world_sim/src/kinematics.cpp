#include "world_sim/kinematics.h"

#include <cmath>

namespace world_sim {

grid::Pose2D IntegrateUnicycle(const grid::Pose2D& pose, double v, double w, double dt) {
  const double dth = w * dt;
  double dx, dy;
  if (std::abs(dth) < 1e-9) {
    // Straight (to second order) when the turn is negligible; avoids dividing by w.
    dx = v * dt * std::cos(pose.yaw + 0.5 * dth);
    dy = v * dt * std::sin(pose.yaw + 0.5 * dth);
  } else {
    const double r = v / w;
    dx = r * (std::sin(pose.yaw + dth) - std::sin(pose.yaw));
    dy = -r * (std::cos(pose.yaw + dth) - std::cos(pose.yaw));
  }
  return {pose.x + dx, pose.y + dy, grid::NormalizeAngle(pose.yaw + dth)};
}

}  // namespace world_sim
