#include "charging_demo/charging_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "charging_demo/keep_out.h"
#include "grid/option_checks.h"

namespace charging_demo {

namespace {

// A new target this far from the planned one is planned for at once.
constexpr double kRetarget = 0.1;
// m/s when reversing off a charger, and the room it keeps behind.
constexpr double kUndockSpeed = 0.15;
constexpr double kRearGap = 0.1;
// m: a search goal this close is reached; one that has not come this much closer within the
// search's hold is taken to be out of reach.
constexpr double kSearchReached = 0.5;
constexpr double kSearchProgress = 1.0;
// Following walls, back within kLoopDistance (m) of where it was at least kLoopMin (s) before,
// going the same way (within kLoopHeading rad): it is going round an island, a pillar or a
// stretch of wall between two doors. (Out of a room by the door it came in by, the robot passes
// its way in going the other way, which is no loop.)
constexpr double kLoopMin = 10.0;
constexpr double kLoopDistance = 0.4;
constexpr double kLoopHeading = M_PI / 4.0;
// Following walls without getting kFollowProgress (m) anywhere for kFollowStuck (s): stuck.
constexpr double kFollowProgress = 0.5;
constexpr double kFollowStuck = 15.0;
// Longest gap between updates fed to the wanderer's timers (a paused simulation, a late call).
constexpr double kMaxStep = 0.5;
// m: a crumb this close is reached.
constexpr double kCrumbReached = 0.3;

}  // namespace

void ValidateOptions(const ControllerOptions& o) {
  ValidateOptions(o.charging);
  ValidateOptions(o.search);
  local_navigation::ValidateOptions(o.navigation);
  grid::RequireAbove("charging keep_out (m)", o.keep_out, 0.0);
  ValidateOptions(o.trail);
  ValidateOptions(o.wall_follow);
  grid::RequireAtLeast("charging follow_after (s)", o.follow_after, 0.0);
  grid::RequireAbove("charging retrace_after (s)", o.retrace_after, 0.0);
  if (!(o.retrace_after < o.charging.approach_timeout))
    throw std::invalid_argument("charging retrace_after must be below approach_timeout (" +
                                std::to_string(o.charging.approach_timeout) + " s), or an approach gives up first; got " +
                                std::to_string(o.retrace_after));
  grid::RequireAbove("charging retrace_reach (m)", o.retrace_reach, 0.0);
  if (!(o.keep_out < o.charging.wait_distance))
    throw std::invalid_argument("charging keep_out must be below wait_distance (" +
                                std::to_string(o.charging.wait_distance) + " m), got " +
                                std::to_string(o.keep_out));
}

ChargingController::ChargingController(const ControllerOptions& options)
    : options_((ValidateOptions(options), options)),
      behaviour_(options.charging),
      nav_(options.navigation),
      wanderer_(options.wander, options.seed),
      rng_(options.seed ^ 0x5bd1e995u),
      search_(options.search),
      trail_(options.trail),
      follower_(options.wall_follow, options.seed % 2 ? Hand::kLeft : Hand::kRight) {}

void ChargingController::OnOdometry(const grid::Pose2D& odom, double time) {
  nav_.OnOdometry(odom, time);
}

void ChargingController::OnRanges(const std::vector<local_navigation::RangeReading>& readings,
                                  double reach, double time) {
  nav_.OnRanges(readings, reach, time);
  ranges_ = readings;
}

void ChargingController::OnSightings(const std::vector<ChargerSighting>& sightings) {
  sightings_.insert(sightings_.end(), sightings.begin(), sightings.end());
}

void ChargingController::OnBattery(double level, bool docked) {
  battery_ = level;
  docked_ = docked;
}

ControllerOutput ChargingController::Update(local_mutex::State lock, double time) {
  const double dt = updated_ ? std::clamp(time - last_update_, 0.0, kMaxStep) : 0.0;
  last_update_ = time;
  updated_ = true;
  nav_.Expire(time);

  ChargingInputs in;
  in.odom = nav_.pose();
  in.battery = battery_;
  in.docked = docked_;
  in.sightings.swap(sightings_);
  in.lock = lock;
  in.time = time;
  // Going back along the trail counts as progress while it keeps getting further back.
  in.making_way = retrace_.active && time - retrace_.moved_back < options_.retrace_after;
  // In view: the local map shows open space up to the charger (or to a docked robot on it).
  const local_navigation::LocalMap& map = nav_.map();
  const Eigen::Vector2d here = nav_.pose().position();
  in.in_view = [&map, here, this](const Eigen::Vector2d& p) {
    return map.ClearView(here, p, options_.navigation.planner.robot_radius + map.resolution());
  };
  const ChargingCommand cmd = behaviour_.Update(in);
  sightings_.clear();
  // Wherever the robot goes it looks for chargers: time spent anywhere is time spent searching.
  if (nav_.have_pose()) {
    search_.Visit(nav_.pose().position(), dt);
    trail_.Visit(nav_.pose().position(), time);
  }
  if (behaviour_.phase() != Phase::kApproach) retrace_.active = false;

  ControllerOutput out;
  out.want_lock = cmd.want_lock;
  if (!nav_.have_pose()) return out;
  local_navigation::Velocity velocity;
  switch (cmd.motion) {
    case ChargingCommand::Motion::kDuty:
      velocity = behaviour_.phase() == Phase::kSeek ? Search(time, dt) : Wander(dt);
      break;
    case ChargingCommand::Motion::kStop:
      nav_.Hold(time);
      planned_for_.reset();
      break;
    case ChargingCommand::Motion::kGoTo:
      velocity = behaviour_.phase() == Phase::kApproach ? Approach(cmd.target, time) : GoTo(cmd.target, time);
      break;
    case ChargingCommand::Motion::kBackAway:
      velocity = BackAway(cmd.target, time);
      break;
  }
  out.v = velocity.v;
  out.w = velocity.w;
  return out;
}

local_navigation::Velocity ChargingController::Search(double time, double dt) {
  const Eigen::Vector2d here = nav_.pose().position();
  if (search_phase_since_ != behaviour_.phase_since()) {
    // A new search (after duty, or after giving up on a charger): nothing carries over.
    search_phase_since_ = behaviour_.phase_since();
    search_goal_.reset();
    search_failed_.reset();
    following_ = false;
    escaping_ = false;
  }
  if (time - behaviour_.phase_since() < options_.follow_after) return SearchGoal(time);
  // Long enough near by: follow walls, which leads out of rooms and into every other.
  if (!following_) {
    following_ = true;
    escaping_ = false;
    follower_.Reset();
    follow_since_ = time;
    loop_checked_ = time;
    follow_progress_at_ = here;
    follow_progress_time_ = time;
  }
  if (escaping_) {
    // Round an island (a pillar, a robot): one search goal away from it, then walls again.
    const local_navigation::Velocity velocity = SearchGoal(time);
    if (goals_chosen_ == escape_goal_) return velocity;
    escaping_ = false;
    follower_.Reset();
    follow_since_ = time;
    follow_progress_at_ = here;
    follow_progress_time_ = time;
  }
  if (time - loop_checked_ >= 1.0) {
    loop_checked_ = time;
    const std::optional<std::uint64_t> last = trail_.LaidBy(time - kLoopMin);
    const std::optional<std::uint64_t> first = trail_.LaidBy(follow_since_);
    const double heading = nav_.pose().yaw;
    // Stuck (caught at the tip of a thin wall, against another robot) counts as a loop too.
    if ((here - follow_progress_at_).norm() > kFollowProgress) {
      follow_progress_at_ = here;
      follow_progress_time_ = time;
    }
    escaping_ = time - follow_progress_time_ > kFollowStuck;
    if (follower_.on_wall() && last && first) {
      for (std::uint64_t i = *first + 1; i < *last && !escaping_; ++i) {
        const Eigen::Vector2d way = trail_.at(i + 1).position - trail_.at(i).position;
        escaping_ = (trail_.at(i).position - here).norm() < kLoopDistance &&
                    std::abs(grid::NormalizeAngle(std::atan2(way.y(), way.x()) - heading)) < kLoopHeading;
      }
    }
    if (escaping_) {
      // Round the same way again: the other hand breaks the loop; one goal away first.
      ++loops_;
      follower_ = WallFollower(options_.wall_follow, follower_.hand() == Hand::kLeft ? Hand::kRight : Hand::kLeft);
      search_goal_.reset();
      const local_navigation::Velocity velocity = SearchGoal(time);
      escape_goal_ = goals_chosen_;
      return velocity;
    }
  }
  planned_for_.reset();
  nav_.ClearPlan();
  return follower_.Update(KeepOutRanges(ranges_, nav_.pose(), behaviour_.known_chargers(), options_.keep_out), dt);
}

local_navigation::Velocity ChargingController::SearchGoal(double time) {
  const Eigen::Vector2d here = nav_.pose().position();
  if (search_goal_ && (*search_goal_ - here).norm() < kSearchReached) search_goal_.reset();
  if (search_goal_ && time - search_since_ > search_.options().hold) {
    // Hardly nearer after all that time: a wall (or the building's edge) is in the way.
    if ((*search_goal_ - here).norm() > search_start_distance_ - kSearchProgress) search_.MarkUnreachable(*search_goal_);
    search_goal_.reset();
  }
  if (!search_goal_) {
    search_goal_ = search_.ChooseGoal(here, nav_.map(), rng_, search_failed_);
    ++goals_chosen_;
    search_since_ = time;
    search_start_distance_ = (*search_goal_ - here).norm();
    search_failed_.reset();
  }
  const local_navigation::Velocity velocity = GoTo(*search_goal_, time);
  if (!nav_.BackingOff(time) && nav_.plan().size() >= 2) return velocity;
  // Walled off, or stuck and backing off: another way next time.
  search_.MarkUnreachable(*search_goal_);
  const Eigen::Vector2d way = *search_goal_ - here;
  search_failed_ = std::atan2(way.y(), way.x());
  search_goal_.reset();
  return velocity;
}

local_navigation::Velocity ChargingController::Wander(double dt) {
  search_goal_.reset();
  planned_for_.reset();
  nav_.ClearPlan();
  const std::vector<local_navigation::RangeReading> seen =
      KeepOutRanges(ranges_, nav_.pose(), behaviour_.known_chargers(), options_.keep_out);
  std::vector<float> ring(seen.size());
  std::transform(seen.begin(), seen.end(), ring.begin(),
                 [](const local_navigation::RangeReading& r) { return static_cast<float>(r.range); });
  const behaviours::VelocityCommand c = wanderer_.Update(ring, dt);
  return {c.v, c.w};
}

local_navigation::Velocity ChargingController::BackAway(const Eigen::Vector2d& charger,
                                                          double time) {
  planned_for_.reset();
  nav_.Hold(time);
  const local_navigation::MotionOptions& m = options_.navigation.motion;
  const grid::Pose2D& pose = nav_.pose();
  const Eigen::Vector2d to = charger - pose.position();
  // Face the charger (as when docked) and reverse, as a robot leaves a dock; stop when
  // something is close behind.
  const double error =
      to.norm() > 1e-6 ? grid::NormalizeAngle(std::atan2(to.y(), to.x()) - pose.yaw) : 0.0;
  local_navigation::Velocity out;
  out.w = std::clamp(m.turn_gain * error, -m.max_turn_rate, m.max_turn_rate);
  const double behind = local_navigation::NearestRange(ranges_, M_PI, M_PI / 3.0);
  if (std::abs(error) < M_PI / 3.0 && behind > options_.navigation.planner.robot_radius + kRearGap)
    out.v = -kUndockSpeed * std::cos(error);
  return out;
}

std::vector<Eigen::Vector2d> ChargingController::OtherChargers() const {
  std::vector<Eigen::Vector2d> others;
  const std::optional<Eigen::Vector2d> in_use = behaviour_.charger();
  for (const Eigen::Vector2d& c : behaviour_.known_chargers())
    if (!in_use || (c - *in_use).norm() >= options_.charging.same_charger) others.push_back(c);
  return others;
}

local_navigation::Velocity ChargingController::Approach(const Eigen::Vector2d& target, double time) {
  const Eigen::Vector2d here = nav_.pose().position();
  const Eigen::Vector2d charger = *behaviour_.charger();
  const bool same = approach_charger_ && approach_since_ == behaviour_.phase_since() &&
                    (*approach_charger_ - charger).norm() < options_.charging.same_charger;
  approach_charger_ = charger;  // it follows the sightings
  if (!same) {
    approach_since_ = behaviour_.phase_since();
    retrace_.active = false;
    retraced_mark_.reset();
  }
  if (!retrace_.active) {
    // The behaviour measures the approach's progress; stalled this long, try the trail.
    if (time - behaviour_.approach_progress_time() > options_.retrace_after) StartRetrace(time);
    if (!retrace_.active) return GoTo(target, time);
  }
  if (retrace_.mark < trail_.oldest()) {
    // The way back has dropped out of the trail's memory: only directly from here on.
    retrace_.active = false;
    retraced_mark_ = retrace_.mark;
    return GoTo(target, time);
  }
  if (nav_.ReplanDue(time) || !planned_for_) {
    // One pass over the local map says which crumbs the robot could plan to from here.
    const local_navigation::Grid<std::uint32_t> costs = nav_.CostsFromRobot(OtherChargers(), options_.keep_out);
    const local_navigation::LocalMap& map = nav_.map();
    const auto reachable = [&](const Eigen::Vector2d& p) {
      const Eigen::Vector2i cell = map.CellOf(p);
      return map.Inside(cell) && costs.at(cell) != local_navigation::kUnreachable;
    };
    const std::optional<std::uint64_t> back =
        trail_.FurthestBack(retrace_.cursor, retrace_.mark, here, options_.retrace_reach, reachable);
    if (back && *back < retrace_.cursor) {
      retrace_.cursor = *back;
      retrace_.moved_back = time;
    }
  }
  const Eigen::Vector2d crumb = trail_.at(retrace_.cursor).position;
  if (retrace_.cursor == retrace_.mark && (crumb - here).norm() < kCrumbReached) {
    // Back where the charger was last seen: from here the way to it is direct.
    retrace_.active = false;
    retraced_mark_ = retrace_.mark;
    return GoTo(target, time);
  }
  return GoTo(crumb, time);
}

bool ChargingController::StartRetrace(double time) {
  if (trail_.empty()) return false;
  const std::optional<std::uint64_t> mark = trail_.LaidBy(behaviour_.charger_seen());
  // Nothing to go back along: seen from here, from beyond the trail's memory, or retraced to.
  if (!mark || *mark + 1 >= trail_.newest() || mark == retraced_mark_) return false;
  retrace_.active = true;
  retrace_.mark = *mark;
  retrace_.cursor = trail_.newest();
  retrace_.moved_back = time;
  planned_for_.reset();
  ++retraces_;
  return true;
}

local_navigation::Velocity ChargingController::GoTo(const Eigen::Vector2d& target, double time) {
  if (nav_.BackingOff(time)) return nav_.BackoffCommand();
  if (!planned_for_ || (*planned_for_ - target).norm() > kRetarget || nav_.ReplanDue(time)) {
    planned_for_ = target;
    // Round every charger but the one in use: never across a charger someone may be docked at.
    nav_.PlanTo(target, time, OtherChargers(), options_.keep_out);
  }
  const local_navigation::LocalNavigator::Steering steering = nav_.Steer(time);
  if (steering.stuck) {
    planned_for_.reset();
    const double turn = (std::bernoulli_distribution(0.5)(rng_) ? 0.5 : -0.5) *
                        options_.navigation.motion.max_turn_rate;
    nav_.StartBackoff(time, turn);
  }
  return steering.command;
}

}  // namespace charging_demo
