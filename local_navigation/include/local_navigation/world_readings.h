#pragma once

#include <cstdint>
#include <vector>

#include "local_navigation/local_navigator.h"
#include "world_sim/world.h"
#include "world_sim/world_config.h"

namespace local_navigation {

// Hands a team's in-process controllers what world_sim has measured, each kind of reading only
// when it is new (world_sim keeps the last reading and the step it was taken at), and the IR
// ring as range readings with their bearings and reach.
class WorldReadings {
 public:
  WorldReadings(const world_sim::RobotModel& body, std::size_t robots);

  struct Fresh {
    bool odom = false, ranges = false, fiducials = false;
  };
  // What is new for robot `k` since the last call for it; fills ranges() when the scan is.
  Fresh Take(std::size_t k, const world_sim::RobotState& state);

  const std::vector<RangeReading>& ranges() const { return ranges_; }
  double reach() const { return reach_; }  // m from the centre

 private:
  std::vector<double> bearings_;
  double reach_ = 0.0;
  std::vector<RangeReading> ranges_;
  std::vector<std::uint64_t> odom_seen_, scan_seen_, camera_seen_;
};

}  // namespace local_navigation
