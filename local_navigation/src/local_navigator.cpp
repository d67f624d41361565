#include "local_navigation/local_navigator.h"

#include <algorithm>
#include <cmath>

#include "grid/option_checks.h"

namespace local_navigation {

using grid::RequireAbove;
using grid::RequireAtLeast;

namespace {

// Reversing speed when backing off after being stuck.
constexpr double kBackoffSpeed = 0.1;

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

void ValidateOptions(const NavigatorOptions& o) {
  ValidateOptions(o.map);
  ValidateOptions(o.planner);
  ValidateOptions(o.motion);
}

double NearestRange(const std::vector<RangeReading>& readings, double bearing, double half_width) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const RangeReading& r : readings)
    if (std::abs(grid::NormalizeAngle(r.bearing - bearing)) <= half_width + 1e-9 && std::isfinite(r.range))
      nearest = std::min(nearest, r.range);
  return nearest;
}

LocalNavigator::LocalNavigator(const NavigatorOptions& options)
    : options_((ValidateOptions(options), options)), map_(options.map) {}

void LocalNavigator::OnOdometry(const grid::Pose2D& odom, double time) {
  pose_ = odom;
  map_.Recentre(pose_.position());
  if (!have_pose_) {
    progress_at_ = pose_.position();
    progress_time_ = time;
  }
  have_pose_ = true;
}

void LocalNavigator::OnRanges(const std::vector<RangeReading>& readings, double reach, double time) {
  if (!have_pose_) return;
  if (!std::isfinite(reach) || reach <= 0.0) {  // a ranger reaching nowhere or forever
    ++bad_scans_;
    return;
  }
  const double half_width =
      options_.clear_sectors && !readings.empty() ? M_PI / readings.size() : 0.0;
  for (const RangeReading& r : readings) map_.AddRange(pose_, r.bearing, r.range, reach, time, half_width);
  front_clearance_ = NearestRange(readings, 0.0, M_PI / 3.0);
  // The robot stands where it is: its own cells are free whatever the beams said.
  map_.MarkFree(pose_.position(), options_.planner.robot_radius, time);
}

bool LocalNavigator::PlanTo(const std::optional<Eigen::Vector2d>& goal, double time,
                            const std::vector<Eigen::Vector2d>& keep_out, double keep_out_radius) {
  last_plan_ = time;
  plan_.clear();
  if (!goal) return false;
  const Eigen::Vector2i start = map_.CellOf(pose_.position());
  const Plan plan = keep_out.empty() || !(keep_out_radius > 0.0)
                        ? MakePlan(map_, start, GoalCell(*goal), options_.planner)
                        : MakePlan(WithKeepOut(keep_out, keep_out_radius), start, GoalCell(*goal), options_.planner);
  ++plans_;
  plan_.reserve(plan.cells.size());
  for (const Eigen::Vector2i& cell : plan.cells) plan_.push_back(map_.CentreOf(cell));
  return !plan_.empty();
}

LocalMap LocalNavigator::WithKeepOut(const std::vector<Eigen::Vector2d>& keep_out, double keep_out_radius) const {
  LocalMap walled = map_;
  if (!(keep_out_radius > 0.0)) return walled;
  const Eigen::Vector2i start = map_.CellOf(pose_.position());
  const int reach = static_cast<int>(std::ceil(keep_out_radius / map_.resolution()));
  for (const Eigen::Vector2d& centre : keep_out) {
    const Eigen::Vector2i c = map_.CellOf(centre);
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        const Eigen::Vector2i cell = c + Eigen::Vector2i(dx, dy);
        // A copy for one plan or pass: the time stamped on these cells is never looked at.
        if (walled.Inside(cell) && cell != start && (map_.CentreOf(cell) - centre).norm() <= keep_out_radius)
          walled.Set(cell, CellState::kOccupied, last_plan_);
      }
  }
  return walled;
}

Grid<std::uint32_t> LocalNavigator::CostsFromRobot(const std::vector<Eigen::Vector2d>& keep_out,
                                                   double keep_out_radius) const {
  const LocalMap walled = WithKeepOut(keep_out, keep_out_radius);
  return Wavefront(PlanningCosts(walled, options_.planner), walled.CellOf(pose_.position()));
}

Eigen::Vector2i LocalNavigator::GoalCell(const Eigen::Vector2d& goal) const {
  const Eigen::Vector2i cell = map_.CellOf(goal);
  const int last = map_.size() - 1;
  return {std::clamp(cell.x(), 0, last), std::clamp(cell.y(), 0, last)};
}

void LocalNavigator::Hold(double time) {
  plan_.clear();
  progress_at_ = pose_.position();
  progress_time_ = time;
}

LocalNavigator::Steering LocalNavigator::Steer(double time) {
  const MotionOptions& m = options_.motion;
  const Eigen::Vector2d here = pose_.position();
  Steering out;
  if (plan_.size() < 2) {
    // Nothing to go to yet: turn on the spot so the rangers sweep the surroundings.
    out.command.w = 0.5 * m.max_turn_rate;
    Hold(time);
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
  out.command.w = std::clamp(m.turn_gain * error, -m.max_turn_rate, m.max_turn_rate);
  if (std::abs(error) < M_PI / 3.0) {
    out.command.v = m.max_speed * std::cos(error);
    // Slow down near the end of the plan so a goal is not overshot.
    out.command.v = std::min(out.command.v, 0.05 + 0.8 * (plan_.back() - here).norm());
    if (front_clearance_ < options_.planner.robot_radius + 0.1) out.command.v = 0.0;
  }

  if ((here - progress_at_).norm() > 0.1) {
    progress_at_ = here;
    progress_time_ = time;
  } else if (time - progress_time_ > m.stuck_time) {
    ++stuck_count_;
    out.stuck = true;
    Hold(time);
  }
  return out;
}

void LocalNavigator::StartBackoff(double time, double turn) {
  backoff_until_ = time + options_.motion.backoff_time;
  backoff_turn_ = turn;
}

Velocity LocalNavigator::BackoffCommand() const { return {-kBackoffSpeed, backoff_turn_}; }

}  // namespace local_navigation
