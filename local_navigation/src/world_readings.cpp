#include "local_navigation/world_readings.h"

#include "world_sim/ir_rangers.h"

namespace local_navigation {

WorldReadings::WorldReadings(const world_sim::RobotModel& body, std::size_t robots)
    : reach_(body.radius + body.ir_range),
      odom_seen_(robots, 0),
      scan_seen_(robots, 0),
      camera_seen_(robots, 0) {
  for (int k = 0; k < body.ir_count; ++k) bearings_.push_back(world_sim::IrAngle(body, k));
  ranges_.resize(bearings_.size());
}

WorldReadings::Fresh WorldReadings::Take(std::size_t k, const world_sim::RobotState& s) {
  Fresh fresh;
  fresh.odom = s.odom_step != odom_seen_[k];
  fresh.ranges = s.scan_step != scan_seen_[k];
  fresh.fiducials = s.fiducials_step != camera_seen_[k];
  odom_seen_[k] = s.odom_step;
  scan_seen_[k] = s.scan_step;
  camera_seen_[k] = s.fiducials_step;
  if (fresh.ranges)
    for (std::size_t b = 0; b < bearings_.size(); ++b) ranges_[b] = {bearings_[b], s.scan[b]};
  return fresh;
}

}  // namespace local_navigation
