#include "world_sim/odometry_drift.h"

#include <cmath>

namespace world_sim {

OdometryDrift::OdometryDrift(const OdometryNoise& noise, std::uint32_t seed)
    : noise_(noise), rng_(seed) {}

const grid::Pose2D& OdometryDrift::Update(const grid::Pose2D& before, const grid::Pose2D& after) {
  if (before.x == after.x && before.y == after.y && before.yaw == after.yaw) {
    return pose_;  // standing still: no drift, no draws
  }
  // The motion in the frame of `before` (what wheel encoders measure).
  const double c = std::cos(before.yaw), s = std::sin(before.yaw);
  const double dx = after.x - before.x, dy = after.y - before.y;
  const grid::Pose2D delta{c * dx + s * dy, -s * dx + c * dy,
                           grid::NormalizeAngle(after.yaw - before.yaw)};
  const double dist = std::sqrt(delta.x * delta.x + delta.y * delta.y);
  const double linear = 1.0 + noise_.linear * unit_normal_(rng_);
  const double angular = 1.0 + noise_.angular * unit_normal_(rng_);
  const grid::Pose2D noisy{delta.x * linear, delta.y * linear,
                           delta.yaw * angular + noise_.heading_bias * dist};
  pose_ = grid::Compose(pose_, noisy);
  return pose_;
}

}  // namespace world_sim
