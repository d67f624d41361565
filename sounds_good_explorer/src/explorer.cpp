#include "sounds_good_explorer/explorer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sounds_good_explorer/frontiers.h"
#include "sounds_good_explorer/marker_packet.h"

#include "sounds_good_explorer/option_checks.h"

namespace sounds_good_explorer {

namespace {

// How long a goal found unreachable stays excluded from the frontier choice.
constexpr double kUnreachableMemory = 30.0;
// Reversing speed when backing off after being stuck.
constexpr double kBackoffSpeed = 0.1;

Eigen::Vector2i Clamp(const Eigen::Vector2i& cell, int size) {
  return {std::clamp(cell.x(), 0, size - 1), std::clamp(cell.y(), 0, size - 1)};
}

}  // namespace

void ValidateOptions(const MotionOptions& o) {
  RequireAbove("motion max_speed (m/s)", o.max_speed, 0.0);
  RequireAbove("motion max_turn_rate (rad/s)", o.max_turn_rate, 0.0);
  RequireAbove("motion turn_gain", o.turn_gain, 0.0);
  RequireAbove("motion lookahead (m)", o.lookahead, 0.0);
  RequireAbove("motion goal_tolerance (m)", o.goal_tolerance, 0.0);
  RequireAbove("motion goal_hold (s)", o.goal_hold, 0.0);
  RequireAbove("motion replan_period (s)", o.replan_period, 0.0);
  RequireAbove("motion stuck_time (s)", o.stuck_time, 0.0);
  RequireAtLeast("motion backoff_time (s)", o.backoff_time, 0.0);
}

void ValidateOptions(const ExplorerOptions& o) {
  ValidateOptions(o.map);
  ValidateOptions(o.planner);
  ValidateOptions(o.frontier);
  ValidateOptions(o.audio);
  ValidateOptions(o.task);
  ValidateOptions(o.motion);
  if (o.task.source > kMaxMarkerId || o.task.sink > kMaxMarkerId)
    throw std::invalid_argument("task marker ids must be at most " + std::to_string(kMaxMarkerId) +
                                " to be announced");
}

Explorer::Explorer(const ExplorerOptions& options)
    : options_((ValidateOptions(options), options)),
      map_(options.map),
      heard_(options.audio),
      task_(options.task),
      rng_(options.seed) {}

void Explorer::OnOdometry(const grid::Pose2D& odom, double time) {
  pose_ = odom;
  map_.Recentre(pose_.position());
  if (!have_pose_) {
    progress_at_ = pose_.position();
    progress_time_ = time;
  }
  have_pose_ = true;
}

void Explorer::OnRanges(const std::vector<RangeReading>& readings, double reach, double time) {
  if (!have_pose_) return;
  if (!std::isfinite(reach) || reach <= 0.0) {  // a ranger reaching nowhere or forever
    ++bad_scans_;
    return;
  }
  front_clearance_ = std::numeric_limits<double>::infinity();
  const double half_width =
      options_.clear_sectors && !readings.empty() ? M_PI / readings.size() : 0.0;
  for (const RangeReading& r : readings) {
    map_.AddRange(pose_, r.bearing, r.range, reach, time, half_width);
    if (std::abs(grid::NormalizeAngle(r.bearing)) <= M_PI / 3.0 && std::isfinite(r.range))
      front_clearance_ = std::min(front_clearance_, r.range);
  }
  // The robot stands where it is: its own cells are free whatever the beams said.
  map_.MarkFree(pose_.position(), options_.planner.robot_radius, time);
}

void Explorer::OnSightings(const std::vector<MarkerSighting>& sightings, double time) {
  if (!have_pose_) return;
  for (const MarkerSighting& s : sightings)
    task_.Seen(s.id, grid::TransformPoint(pose_, {s.range * std::cos(s.bearing),
                                                  s.range * std::sin(s.bearing)}),
               time);
}

void Explorer::OnHeard(const std::vector<std::uint8_t>& data, double level_db, double direction,
                       double time) {
  const std::optional<std::uint32_t> marker = DecodeMarkerPacket(data);
  if (!marker) {
    ++foreign_packets_;
    return;
  }
  heard_.Add(*marker, direction, pose_.yaw, level_db, time, options_.mode);
}

ExplorerOutput Explorer::Update(double time) {
  ExplorerOutput out;
  map_.Expire(time);
  heard_.Forget(time);
  const Eigen::Vector2d here = pose_.position();
  out.job = task_.Update(here, time);
  if (out.job) {
    goal_.reset();
    unreachable_.clear();
  }
  for (std::uint32_t marker : task_.DueAnnouncements(time)) {
    // An id the 16-bit announcement cannot carry (another robot's charger, say) goes unsaid.
    if (marker <= kMaxMarkerId) out.packets.push_back(EncodeMarkerPacket(marker));
    else ++unannounced_;
  }
  if (!have_pose_ || task_.working()) {
    plan_.clear();
    progress_at_ = here;
    progress_time_ = time;
    return out;
  }
  if (time < backoff_until_) {
    out.v = -kBackoffSpeed;
    out.w = backoff_turn_;
    return out;
  }

  const std::optional<Eigen::Vector2d> marker = task_.SoughtPosition(time);
  bool new_goal = false;
  if (marker) {
    new_goal = !goal_is_marker_ || !goal_;
    goal_ = marker;
    goal_is_marker_ = true;
  } else if (!goal_ || goal_is_marker_ || (*goal_ - here).norm() <= options_.motion.goal_tolerance ||
             time - goal_chosen_ >= options_.motion.goal_hold) {
    ChooseGoal(time);
    new_goal = true;
  }
  if (new_goal || time - last_plan_ >= options_.motion.replan_period) Replan(time);
  return Steer(time, out);
}

void Explorer::ChooseGoal(double time) {
  goal_is_marker_ = false;
  goal_chosen_ = time;
  unreachable_.erase(std::remove_if(unreachable_.begin(), unreachable_.end(),
                                    [&](const auto& u) { return time - u.second > kUnreachableMemory; }),
                     unreachable_.end());
  std::vector<Eigen::Vector2i> excluded;
  for (const auto& u : unreachable_) excluded.push_back(u.first - map_.origin());
  goal_.reset();
  const std::optional<Eigen::Vector2i> cell =
      ChooseFrontier(map_, FindFrontiers(map_), pose_.position(), heard_, task_.sought(), time,
                     options_.frontier, rng_, excluded);
  if (cell) goal_ = map_.CentreOf(*cell);
}

void Explorer::Replan(double time) {
  last_plan_ = time;
  plan_.clear();
  if (!goal_) return;
  const Eigen::Vector2i goal_cell = Clamp(map_.CellOf(*goal_), map_.size());
  const Plan plan = MakePlan(map_, map_.CellOf(pose_.position()), goal_cell, options_.planner);
  ++plans_;
  if (plan.cells.empty()) {
    // Walled off in the local map: remember not to choose it again for a while.
    if (!goal_is_marker_) unreachable_.emplace_back(goal_cell + map_.origin(), time);
    goal_.reset();
    return;
  }
  plan_.reserve(plan.cells.size());
  for (const Eigen::Vector2i& cell : plan.cells) plan_.push_back(map_.CentreOf(cell));
}

ExplorerOutput Explorer::Steer(double time, ExplorerOutput out) {
  const MotionOptions& m = options_.motion;
  const Eigen::Vector2d here = pose_.position();
  if (plan_.size() < 2) {
    // Nothing to go to yet: turn on the spot so the rangers sweep the surroundings.
    out.w = 0.5 * m.max_turn_rate;
    progress_at_ = here;
    progress_time_ = time;
    return out;
  }
  Eigen::Vector2d target = plan_.back();
  for (std::size_t i = 1; i < plan_.size(); ++i) {
    if ((plan_[i] - here).norm() >= m.lookahead) {
      target = plan_[i];
      break;
    }
  }
  const Eigen::Vector2d to = target - here;
  const double error = grid::NormalizeAngle(std::atan2(to.y(), to.x()) - pose_.yaw);
  out.w = std::clamp(m.turn_gain * error, -m.max_turn_rate, m.max_turn_rate);
  if (std::abs(error) < M_PI / 3.0) {
    out.v = m.max_speed * std::cos(error);
    // Slow down near the end of the plan so a marker is not overshot.
    out.v = std::min(out.v, 0.05 + 0.8 * (plan_.back() - here).norm());
    if (front_clearance_ < options_.planner.robot_radius + 0.1) out.v = 0.0;
  }

  if ((here - progress_at_).norm() > 0.1) {
    progress_at_ = here;
    progress_time_ = time;
  } else if (time - progress_time_ > m.stuck_time) {
    ++stuck_count_;
    if (goal_ && !goal_is_marker_) unreachable_.emplace_back(map_.CellOf(*goal_) + map_.origin(), time);
    goal_.reset();
    plan_.clear();
    backoff_until_ = time + m.backoff_time;
    backoff_turn_ = (std::bernoulli_distribution(0.5)(rng_) ? 0.5 : -0.5) * m.max_turn_rate;
    progress_at_ = here;
    progress_time_ = time;
  }
  return out;
}

}  // namespace sounds_good_explorer
