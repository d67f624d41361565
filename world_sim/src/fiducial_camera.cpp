#include "world_sim/fiducial_camera.h"

#include <algorithm>
#include <cmath>

#include "grid/line_of_sight.h"

namespace world_sim {

std::vector<FiducialSighting> SeeFiducials(const grid::OccupancyMap& map, const RobotModel& model,
                                           const grid::Pose2D& pose,
                                           const std::vector<MarkerSpec>& markers) {
  std::vector<FiducialSighting> seen;
  const Eigen::Vector2d eye = pose.position();
  for (const MarkerSpec& m : markers) {
    const Eigen::Vector2d to(m.x - eye.x(), m.y - eye.y());
    const double range = to.norm();
    if (range > model.camera_range) continue;
    const double bearing = grid::NormalizeAngle(std::atan2(to.y(), to.x()) - pose.yaw);
    if (model.camera_fov < 2.0 * M_PI && std::abs(bearing) > 0.5 * model.camera_fov) continue;
    if (!grid::LineOfSight(map, eye, {m.x, m.y})) continue;
    seen.push_back({m.id, range, bearing});
  }
  std::sort(seen.begin(), seen.end(), [](const FiducialSighting& a, const FiducialSighting& b) {
    return a.range < b.range || (a.range == b.range && a.id < b.id);
  });
  return seen;
}

}  // namespace world_sim
