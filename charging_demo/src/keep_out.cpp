#include "charging_demo/keep_out.h"

#include <algorithm>
#include <cmath>

namespace charging_demo {

std::vector<local_navigation::RangeReading> KeepOutRanges(
    const std::vector<local_navigation::RangeReading>& readings, const grid::Pose2D& pose,
    const std::vector<Eigen::Vector2d>& centres, double radius) {
  std::vector<local_navigation::RangeReading> out = readings;
  const Eigen::Vector2d p = pose.position();
  for (local_navigation::RangeReading& r : out) {
    const double angle = pose.yaw + r.bearing;
    const Eigen::Vector2d u(std::cos(angle), std::sin(angle));
    for (const Eigen::Vector2d& c : centres) {
      // |p + t u - c| = radius: t^2 + 2 b t + k = 0 with b = u.(p - c), k = |p - c|^2 - r^2.
      const Eigen::Vector2d d = p - c;
      const double b = u.dot(d);
      const double k = d.squaredNorm() - radius * radius;
      double hit;
      if (k <= 0.0) {
        if (b >= 0.0) continue;  // inside, looking out
        hit = 0.0;
      } else {
        const double disc = b * b - k;
        if (disc < 0.0 || b >= 0.0) continue;  // misses, or the disc is behind
        hit = -b - std::sqrt(disc);
      }
      if (!(r.range <= hit)) r.range = hit;  // NaN and +inf ("nothing") are cut too
    }
  }
  return out;
}

}  // namespace charging_demo
