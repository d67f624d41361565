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
#include "local_navigation/local_map.h"
#include "local_navigation/local_navigator.h"
#include "local_navigation/planner.h"
#include "sounds_good_explorer/frontier_choice.h"
#include "sounds_good_explorer/heard_messages.h"
#include "sounds_good_explorer/listen_mode.h"
#include "sounds_good_explorer/transport_task.h"

namespace sounds_good_explorer {

struct ExplorerOptions {
  ListenMode mode = ListenMode::kBidirectional;
  // Navigation (see local_navigation::NavigatorOptions).
  local_navigation::LocalMapOptions map;
  bool clear_sectors = true;
  local_navigation::PlannerOptions planner;
  FrontierOptions frontier;
  AudioTermOptions audio;
  TaskOptions task;
  local_navigation::MotionOptions motion;
  std::uint32_t seed = 1;
};

// Throws std::invalid_argument naming the field of the first impossible option.
void ValidateOptions(const ExplorerOptions& options);

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

  // See local_navigation::LocalNavigator.
  void OnOdometry(const grid::Pose2D& odom, double time) { nav_.OnOdometry(odom, time); }
  void OnRanges(const std::vector<local_navigation::RangeReading>& readings, double reach,
                double time) {
    nav_.OnRanges(readings, reach, time);
  }
  void OnSightings(const std::vector<MarkerSighting>& sightings, double time);
  // A packet heard: level in dB, direction in the robot frame (NaN when unknown). Packets
  // that are not marker announcements are ignored (and counted).
  void OnHeard(const std::vector<std::uint8_t>& data, double level_db, double direction,
               double time);

  ExplorerOutput Update(double time);

  const grid::Pose2D& pose() const { return nav_.pose(); }
  const local_navigation::LocalMap& local_map() const { return nav_.map(); }
  const std::vector<Eigen::Vector2d>& plan() const { return nav_.plan(); }  // odom frame
  std::optional<Eigen::Vector2d> goal() const { return goal_; }       // odom frame
  bool goal_is_marker() const { return goal_is_marker_; }
  const TransportTask& task() const { return task_; }
  const HeardMessages& heard() const { return heard_; }
  std::uint64_t foreign_packets() const { return foreign_packets_; }
  std::uint64_t stuck_count() const { return nav_.stuck_count(); }
  std::uint64_t plans() const { return nav_.plans(); }
  std::uint64_t bad_scans() const { return nav_.bad_scans(); }
  std::uint64_t unannounced() const { return unannounced_; }  // markers whose id does not fit

 private:
  void ChooseGoal(double time);
  void Replan(double time);
  ExplorerOutput Steer(double time, ExplorerOutput out);

  ExplorerOptions options_;
  local_navigation::LocalNavigator nav_;
  HeardMessages heard_;
  TransportTask task_;
  std::mt19937 rng_;
  std::optional<Eigen::Vector2d> goal_;
  bool goal_is_marker_ = false;
  double goal_chosen_ = -1e9;
  // Goals that could not be reached: odom-frame cell and when.
  std::vector<std::pair<Eigen::Vector2i, double>> unreachable_;
  std::uint64_t foreign_packets_ = 0, unannounced_ = 0;
};

}  // namespace sounds_good_explorer
