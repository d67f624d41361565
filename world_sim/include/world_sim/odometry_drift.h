#pragma once

#include <cstdint>
#include <random>

#include "grid/pose2d.h"
#include "world_sim/world_config.h"

namespace world_sim {

// Dead reckoning that drifts from the truth: each true motion increment is scaled by noisy
// factors before it is added to the odometry pose, so the error grows with distance and
// rotation as wheel odometry's does. Deterministic for a given seed.
class OdometryDrift {
 public:
  OdometryDrift(const OdometryNoise& noise, std::uint32_t seed);

  // Adds the motion from true pose `before` to `after`; returns the new odometry pose
  // (which starts at the origin of the robot's odom frame).
  const grid::Pose2D& Update(const grid::Pose2D& before, const grid::Pose2D& after);
  const grid::Pose2D& pose() const { return pose_; }

 private:
  OdometryNoise noise_;
  std::mt19937 rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
  grid::Pose2D pose_;
};

}  // namespace world_sim
