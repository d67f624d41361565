#include "world_sim/ir_rangers.h"

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "grid/line_of_sight.h"
#include "world_sim/collision.h"

namespace world_sim {

double IrAngle(const RobotModel& model, int k) { return 2.0 * M_PI * k / model.ir_count; }

std::vector<float> IrRanges(const grid::OccupancyMap& map, const RobotModel& model,
                            const grid::Pose2D& pose, const std::vector<Eigen::Vector2d>& others) {
  const double reach = model.radius + model.ir_range;
  const Eigen::Vector2d origin = pose.position();
  std::vector<float> ranges(model.ir_count, std::numeric_limits<float>::infinity());
  // Rotate one beam by the fixed spacing instead of taking sin and cos per beam.
  const double spacing = 2.0 * M_PI / model.ir_count;
  const Eigen::Rotation2Dd turn(spacing);
  Eigen::Vector2d dir(std::cos(pose.yaw), std::sin(pose.yaw));
  for (int k = 0; k < model.ir_count; ++k, dir = turn * dir) {
    double best = reach;
    bool hit = false;
    if (const auto wall = grid::CastRay(map, origin, dir, reach)) {
      best = *wall;
      hit = true;
    }
    for (const Eigen::Vector2d& other : others) {
      if ((other - origin).squaredNorm() > (reach + model.radius) * (reach + model.radius)) continue;
      const auto t = RayHitsDisc(origin, dir, other, model.radius);
      if (t && *t <= best) {
        best = *t;
        hit = true;
      }
    }
    if (hit) ranges[k] = static_cast<float>(best);
  }
  return ranges;
}

}  // namespace world_sim
