#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "grid/pose2d.h"
#include "sounds_good_explorer/frontier_choice.h"
#include "sounds_good_explorer/heard_messages.h"
#include "sounds_good_explorer/listen_mode.h"
#include "sounds_good_explorer/local_map.h"
#include "sounds_good_explorer/planner.h"
#include "sounds_good_explorer/transport_task.h"

namespace sounds_good_explorer {

struct MotionOptions {
  double max_speed = 0.3;      // m/s
  double max_turn_rate = 2.0;  // rad/s
  double turn_gain = 2.5;      // rad/s per rad of heading error
  double lookahead = 0.45;     // m along the plan to steer at
  double goal_tolerance = 0.3;  // m: a frontier goal this close is reached
  double goal_hold = 4.0;      // s a frontier goal is kept before choosing again
  double replan_period = 0.8;  // s between plans
  double stuck_time = 4.0;     // s without moving 0.1 m while following a plan: stuck
  double backoff_time = 1.5;   // s of reversing and turning when stuck
};

void ValidateOptions(const MotionOptions& options);

struct ExplorerOptions {
  ListenMode mode = ListenMode::kBidirectional;
  LocalMapOptions map;
  // Each range reading also clears its share of the ring (pi / readings either side of its
  // bearing, up to its range), so eight narrow rangers map the whole disc around the robot as
  // the thesis's local maps show; false marks only the beams themselves.
  bool clear_sectors = true;
  PlannerOptions planner;
  FrontierOptions frontier;
  AudioTermOptions audio;
  TaskOptions task;
  MotionOptions motion;
  std::uint32_t seed = 1;
};

// Throws std::invalid_argument naming the field of the first impossible option.
void ValidateOptions(const ExplorerOptions& options);

struct RangeReading {
  double bearing = 0.0;  // rad, robot frame
  double range = 0.0;    // m from the robot's centre; +inf or NaN: nothing in reach
};

struct MarkerSighting {
  std::uint32_t id = 0;
  double range = 0.0;    // m
  double bearing = 0.0;  // rad, robot frame
};

struct ExplorerOutput {
  double v = 0.0, w = 0.0;  // velocity command
  std::vector<std::array<std::uint8_t, 4>> packets;  // announcements to send now
  std::optional<Job> job;   // a job finished in this update
};

// The Sounds Good robot (thesis chapter 3): a local-map frontier explorer that carries out the
// transport task and uses heard marker announcements in its frontier choice. Everything is in
// the robot's odometry frame; it needs no map and no global position. Feed it odometry,
// ranges, sightings and receptions as they come, and call Update() at the control rate.
// Deterministic for a seed and the same inputs.
class Explorer {
 public:
  explicit Explorer(const ExplorerOptions& options);

  void OnOdometry(const grid::Pose2D& odom, double time);
  // One sweep of the rangers, taken at the last odometry pose; `reach` is their range from the
  // centre (readings at or beyond it, +inf or NaN, are "nothing"). A sweep whose reach is not a
  // finite positive number is ignored and counted (bad_scans).
  void OnRanges(const std::vector<RangeReading>& readings, double reach, double time);
  void OnSightings(const std::vector<MarkerSighting>& sightings, double time);
  // A packet heard: level in dB, direction in the robot frame (NaN when unknown). Packets
  // that are not marker announcements are ignored (and counted).
  void OnHeard(const std::vector<std::uint8_t>& data, double level_db, double direction,
               double time);

  ExplorerOutput Update(double time);

  const grid::Pose2D& pose() const { return pose_; }
  const LocalMap& local_map() const { return map_; }
  const std::vector<Eigen::Vector2d>& plan() const { return plan_; }  // odom frame
  std::optional<Eigen::Vector2d> goal() const { return goal_; }       // odom frame
  bool goal_is_marker() const { return goal_is_marker_; }
  const TransportTask& task() const { return task_; }
  const HeardMessages& heard() const { return heard_; }
  std::uint64_t foreign_packets() const { return foreign_packets_; }
  std::uint64_t stuck_count() const { return stuck_count_; }
  std::uint64_t plans() const { return plans_; }
  std::uint64_t bad_scans() const { return bad_scans_; }
  std::uint64_t unannounced() const { return unannounced_; }  // markers whose id does not fit

 private:
  void ChooseGoal(double time);
  void Replan(double time);
  ExplorerOutput Steer(double time, ExplorerOutput out);

  ExplorerOptions options_;
  LocalMap map_;
  HeardMessages heard_;
  TransportTask task_;
  std::mt19937 rng_;
  grid::Pose2D pose_;
  bool have_pose_ = false;
  std::optional<Eigen::Vector2d> goal_;
  bool goal_is_marker_ = false;
  double goal_chosen_ = -1e9;
  double last_plan_ = -1e9;
  // Goals that could not be reached: odom-frame cell and when.
  std::vector<std::pair<Eigen::Vector2i, double>> unreachable_;
  double front_clearance_ = std::numeric_limits<double>::infinity();  // m, nearest range ahead
  std::vector<Eigen::Vector2d> plan_;
  // Stuck detection: where the robot was when progress was last checked.
  Eigen::Vector2d progress_at_{0.0, 0.0};
  double progress_time_ = 0.0;
  double backoff_until_ = -1e9;
  double backoff_turn_ = 1.0;
  std::uint64_t foreign_packets_ = 0, stuck_count_ = 0, plans_ = 0, bad_scans_ = 0, unannounced_ = 0;
};

}  // namespace sounds_good_explorer
