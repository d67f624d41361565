#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "grid/pose2d.h"
#include "local_navigation/local_map.h"
#include "local_navigation/planner.h"

namespace local_navigation {

struct MotionOptions {
  double max_speed = 0.3;      // m/s
  double max_turn_rate = 2.0;  // rad/s
  double turn_gain = 2.5;      // rad/s per rad of heading error
  double lookahead = 0.45;     // m along the plan to steer at
  double goal_tolerance = 0.3;  // m: a frontier goal this close is reached (explorer only)
  double goal_hold = 4.0;      // s a frontier goal is kept before choosing again (explorer only)
  double replan_period = 0.8;  // s between plans
  double stuck_time = 4.0;     // s without moving 0.1 m while following a plan: stuck
  double backoff_time = 1.5;   // s of reversing and turning when stuck
};

void ValidateOptions(const MotionOptions& options);

struct NavigatorOptions {
  LocalMapOptions map;
  // Each range reading also clears its share of the ring (pi / readings either side of its
  // bearing, up to its range), so eight narrow rangers map the whole disc around the robot as
  // the thesis's local maps show; false marks only the beams themselves.
  bool clear_sectors = true;
  PlannerOptions planner;
  MotionOptions motion;
};

void ValidateOptions(const NavigatorOptions& options);

struct RangeReading {
  double bearing = 0.0;  // rad, robot frame
  double range = 0.0;    // m from the robot's centre; +inf or NaN: nothing in reach
};

// The nearest finite reading within `half_width` rad of `bearing` (robot frame); +inf when none.
double NearestRange(const std::vector<RangeReading>& readings, double bearing, double half_width);

struct Velocity {
  double v = 0.0, w = 0.0;
};

// Navigation on the thesis's local map (section 3.3), shared by every controller that drives
// with no global map: odometry and range sweeps build the odom-frame LocalMap; PlanTo() runs
// the planner towards a goal (clamped into the map, so a far goal is approached greedily);
// Steer() follows the plan and reports when the robot has made no progress for stuck_time,
// after which the caller decides what to forget and starts a backoff.
class LocalNavigator {
 public:
  explicit LocalNavigator(const NavigatorOptions& options);

  void OnOdometry(const grid::Pose2D& odom, double time);
  // One sweep of the rangers, taken at the last odometry pose; `reach` is their range from the
  // centre (readings at or beyond it, +inf or NaN, are "nothing"). A sweep whose reach is not a
  // finite positive number is ignored and counted (bad_scans).
  void OnRanges(const std::vector<RangeReading>& readings, double reach, double time);
  void Expire(double time) { map_.Expire(time); }

  // Plans from the robot to `goal` (odom frame); false, with no plan, when the local map walls
  // it off or there is no goal. Remembers the time for ReplanDue() either way. Discs of
  // `keep_out_radius` around `keep_out` (odom frame) are planned round as if they were walls:
  // places the robot must not cross, such as chargers other robots may be using.
  bool PlanTo(const std::optional<Eigen::Vector2d>& goal, double time,
              const std::vector<Eigen::Vector2d>& keep_out = {}, double keep_out_radius = 0.0);
  // Least planning cost from the robot to each local-map cell, kUnreachable where walls or the
  // keep-out discs cut it off (unknown cells count as free, as when planning). One pass gives
  // the caller every place it could plan to from here.
  Grid<std::uint32_t> CostsFromRobot(const std::vector<Eigen::Vector2d>& keep_out = {},
                                     double keep_out_radius = 0.0) const;
  // The local-map cell a goal is planned to: its own, or the nearest on the map's edge.
  Eigen::Vector2i GoalCell(const Eigen::Vector2d& goal) const;
  bool ReplanDue(double time) const { return time - last_plan_ >= options_.motion.replan_period; }
  void ClearPlan() { plan_.clear(); }
  // The robot is meant to stand where it is (working, waiting): no plan, and the stuck clock
  // starts again from here.
  void Hold(double time);

  struct Steering {
    Velocity command;
    bool stuck = false;  // no progress for stuck_time: the plan has been dropped
  };
  // Follows the plan (with no plan: turns on the spot so the rangers sweep around).
  Steering Steer(double time);

  // Reverses, turning at `turn` rad/s, for backoff_time.
  void StartBackoff(double time, double turn);
  bool BackingOff(double time) const { return time < backoff_until_; }
  Velocity BackoffCommand() const;

  bool have_pose() const { return have_pose_; }
  const grid::Pose2D& pose() const { return pose_; }
  const LocalMap& map() const { return map_; }
  const std::vector<Eigen::Vector2d>& plan() const { return plan_; }  // odom frame
  // The nearest range within 60 degrees of straight ahead (m; +inf when nothing).
  double front_clearance() const { return front_clearance_; }
  const NavigatorOptions& options() const { return options_; }
  std::uint64_t stuck_count() const { return stuck_count_; }
  std::uint64_t plans() const { return plans_; }
  std::uint64_t bad_scans() const { return bad_scans_; }

 private:
  // The local map with the keep-out discs (but never the robot's own cell) made walls.
  LocalMap WithKeepOut(const std::vector<Eigen::Vector2d>& keep_out, double keep_out_radius) const;

  NavigatorOptions options_;
  LocalMap map_;
  grid::Pose2D pose_;
  bool have_pose_ = false;
  double front_clearance_ = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector2d> plan_;
  double last_plan_ = -1e9;
  // Stuck detection: where the robot was when progress was last checked.
  Eigen::Vector2d progress_at_{0.0, 0.0};
  double progress_time_ = 0.0;
  double backoff_until_ = -1e9;
  double backoff_turn_ = 1.0;
  std::uint64_t stuck_count_ = 0, plans_ = 0, bad_scans_ = 0;
};

}  // namespace local_navigation
