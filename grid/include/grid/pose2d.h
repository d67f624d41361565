#pragma once

#include <cmath>

#include <Eigen/Core>

namespace grid {

// A pose in the plane: position in metres and heading in radians (CCW, REP-103).
struct Pose2D {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;

  Eigen::Vector2d position() const { return {x, y}; }
};

// Every number of the pose is finite: what a pose from a sensor, a file or a peer must be.
inline bool IsFinite(const Pose2D& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.yaw); }

// Wraps an angle into (-pi, pi].
inline double NormalizeAngle(double a) {
  // Simulation steps overshoot by at most a turn; handle that without a library call.
  if (a > M_PI && a <= 3.0 * M_PI) return a - 2.0 * M_PI;
  if (a <= -M_PI && a > -3.0 * M_PI) return a + 2.0 * M_PI;
  if (a > -M_PI && a <= M_PI) return a;
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

// `child` expressed in `parent`'s frame, returned in the frame `parent` lives in.
inline Pose2D Compose(const Pose2D& parent, const Pose2D& child) {
  const double c = std::cos(parent.yaw), s = std::sin(parent.yaw);
  return {parent.x + c * child.x - s * child.y, parent.y + s * child.x + c * child.y,
          NormalizeAngle(parent.yaw + child.yaw)};
}

inline Pose2D Inverse(const Pose2D& p) {
  const double c = std::cos(p.yaw), s = std::sin(p.yaw);
  return {-c * p.x - s * p.y, s * p.x - c * p.y, NormalizeAngle(-p.yaw)};
}

// A point given in `frame`'s coordinates, expressed in the frame `frame` lives in.
inline Eigen::Vector2d TransformPoint(const Pose2D& frame, const Eigen::Vector2d& p) {
  const double c = std::cos(frame.yaw), s = std::sin(frame.yaw);
  return {frame.x + c * p.x() - s * p.y(), frame.y + s * p.x() + c * p.y()};
}

}  // namespace grid
