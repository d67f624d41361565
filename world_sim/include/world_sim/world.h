#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "grid/occupancy_map.h"
#include "grid/pose2d.h"
#include "world_sim/fiducial_camera.h"
#include "world_sim/odometry_drift.h"
#include "world_sim/world_config.h"

namespace world_sim {

struct WorldOptions {
  double step = 0.02;           // s of simulated time per Step()
  double scan_period = 0.1;     // s between IR scans (each period is rounded to whole steps)
  double camera_period = 0.2;   // s between fiducial images
  double odom_period = 0.04;    // s between odometry updates (25 Hz)
  double start_time = 1.0;      // s; never 0, which ROS reads as "no time yet"
};

// Throws std::invalid_argument naming the field, its value and what was expected: step within
// (0, 1] s, start_time above 0, each sensor period finite and at least one step.
void ValidateOptions(const WorldOptions& options);

// How many whole steps make up `period` (at least one): sensor and publishing periods are
// rounded to whole steps.
std::uint64_t StepsPerPeriod(double period, double step);

// One robot as the world sees it. Readings carry the step count they were taken at, so a
// publisher can tell new readings from old.
struct RobotState {
  std::string name;
  grid::Pose2D pose;         // true pose in the map frame
  grid::Pose2D odom;         // dead-reckoned pose in the robot's odom frame, every odom_period
  double v = 0.0, w = 0.0;   // velocities actually achieved in the last step
  double cmd_v = 0.0, cmd_w = 0.0;  // commanded velocities, after clamping
  bool stalled = false;      // the last step's motion was stopped by a collision
  int collisions = 0;        // times the robot started touching a wall or a robot
  double distance = 0.0;     // m driven in all
  double battery = 1.0;      // level, 0 to 1
  bool docked = false;       // within a charger's zone
  std::uint64_t odom_step = 0;
  std::vector<float> scan;   // IR ranges (see IrRanges)
  std::uint64_t scan_step = 0;
  std::vector<FiducialSighting> fiducials;
  std::uint64_t fiducials_step = 0;
};

// A deterministic 2D multi-robot world in the spirit of Stage: robots are discs with unicycle
// kinematics that stop when they would touch a wall or another robot. Every Step() advances a
// fixed time, updates robots in order, and takes sensor readings at their periods. The same
// map, config and options give the same trajectories for the same commands.
class World {
 public:
  // Throws std::invalid_argument on impossible options (ValidateOptions) and grid::InputError on
  // a config that does not fit the map.
  World(grid::OccupancyMap map, WorldConfig config, const WorldOptions& options = {});

  // Commands robot `index` (clamped to the model's limits; ignored while the battery is empty).
  void SetCommand(std::size_t index, double v, double w);
  void Step();

  double time() const { return options_.start_time + steps_ * options_.step; }
  double elapsed() const { return steps_ * options_.step; }
  std::uint64_t steps() const { return steps_; }
  double StepTime(std::uint64_t step) const { return options_.start_time + step * options_.step; }

  std::optional<std::size_t> RobotIndex(const std::string& name) const;
  const std::vector<RobotState>& robots() const { return robots_; }
  const grid::OccupancyMap& map() const { return map_; }
  const WorldConfig& config() const { return config_; }
  const WorldOptions& options() const { return options_; }
  // The fiducials the cameras look for: the markers and the chargers that carry one.
  const std::vector<MarkerSpec>& fiducials() const { return fiducials_; }

  int TotalCollisions() const;
  double TotalDistance() const;

 private:
  void MoveRobot(std::size_t index);
  bool Collides(std::size_t index, const Eigen::Vector2d& centre) const;
  bool Docked(const Eigen::Vector2d& centre) const;
  void TakeReadings();

  grid::OccupancyMap map_;
  WorldConfig config_;
  WorldOptions options_;
  std::vector<RobotState> robots_;
  std::vector<OdometryDrift> drift_;
  std::vector<grid::Pose2D> odom_anchor_;  // true pose at each robot's last odometry update
  std::vector<MarkerSpec> fiducials_;
  std::uint64_t steps_ = 0;
  std::uint64_t scan_every_ = 1;
  std::uint64_t camera_every_ = 1;
  std::uint64_t odom_every_ = 1;
};

}  // namespace world_sim
