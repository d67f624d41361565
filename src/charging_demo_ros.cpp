#include "charging_demo_ros.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <geometry_msgs/Twist.h>
#include <multirobot_audio/ChargingState.h>
#include <std_srvs/Trigger.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.h"
#include "input_checks.h"
#include "navigation_conversions.h"
#include "navigation_params.h"
#include "params.h"

namespace multirobot_audio {
namespace {

using local_mutex::State;

constexpr int kMaxInt = std::numeric_limits<int>::max();
constexpr double kBig = 1e6;
// s of ROS time between repeats of a lock command that has not shown its effect yet (a goal
// for a lock that is still not HELD, a release for one that is still not RELEASED).
constexpr double kLockRetry = 2.0;
// s without odometry or battery before the node says what it waits for.
constexpr double kInputsPatience = 5.0;

unsigned long Count(std::uint64_t n) { return static_cast<unsigned long>(n); }

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// A battery level in (0, 1), or (0, 1] when `one_allowed`: the thresholds.
double FractionParam(const ros::NodeHandle& pnh, const std::string& name, double fallback, bool one_allowed) {
  const double v = NumberParam(pnh, name, fallback, -kBig, kBig);
  if (v <= 0.0 || v > 1.0 || (!one_allowed && v == 1.0)) {
    throw ParamError(pnh.resolveName(name) + ": expected a battery level in (0, 1" + (one_allowed ? "]" : ")") +
                     ", got " + Number(v));
  }
  return v;
}


}  // namespace

ChargingDemoNodeOptions ReadChargingDemoNodeOptions(const ros::NodeHandle& pnh, std::uint32_t default_seed) {
  ChargingDemoNodeOptions o;
  charging_demo::ControllerOptions& c = o.controller;

  charging_demo::ChargingOptions& ch = c.charging;
  for (const int id : RequiredIntListParam(pnh, "chargers", 0, kMaxInt)) ch.chargers.insert(static_cast<std::uint32_t>(id));
  ch.low_battery = FractionParam(pnh, "low_battery", ch.low_battery, false);
  ch.full_battery = FractionParam(pnh, "full_battery", ch.full_battery, true);
  if (ch.full_battery <= ch.low_battery) {
    throw ParamError(pnh.resolveName("full_battery") + ": expected a level above low_battery (" + Number(ch.low_battery) +
                     "), got " + Number(ch.full_battery));
  }
  ch.wait_distance = PositiveParam(pnh, "wait_distance", ch.wait_distance, 100.0);
  ch.arrive_tolerance = PositiveParam(pnh, "arrive_tolerance", ch.arrive_tolerance, 100.0);
  ch.undock_distance = PositiveParam(pnh, "undock_distance", ch.undock_distance, 100.0);
  ch.undock_timeout = PositiveParam(pnh, "undock_timeout", ch.undock_timeout);
  ch.undock_min_distance = PositiveParam(pnh, "undock_min_distance", ch.undock_min_distance, 100.0);
  ch.lock_timeout = PositiveParam(pnh, "lock_timeout", ch.lock_timeout);
  ch.avoid_time = NumberParam(pnh, "avoid_time", ch.avoid_time, 0.0, kBig);
  ch.dock_timeout = PositiveParam(pnh, "dock_timeout", ch.dock_timeout);
  ch.max_redocks = IntParam(pnh, "max_redocks", ch.max_redocks, 0, 1000000);
  ch.approach_timeout = PositiveParam(pnh, "approach_timeout", ch.approach_timeout);
  ch.same_charger = PositiveParam(pnh, "same_charger", ch.same_charger, 100.0);
  ch.recheck_distance = PositiveParam(pnh, "recheck_distance", ch.recheck_distance, 100.0);
  ch.recheck_time = PositiveParam(pnh, "recheck_time", ch.recheck_time);

  // The local-map navigation, with the same names in every node that drives with it.
  local_navigation::NavigatorOptions& n = c.navigation;
  ReadNavigationParams(pnh, n.map, n.clear_sectors, n.planner, n.motion);

  // The duty: wandering, with the wanderer node's names.
  behaviours::WanderOptions& w = c.wander;
  w.cruise_speed = PositiveParam(pnh, "cruise_speed", w.cruise_speed, 100.0);
  w.turn_rate = PositiveParam(pnh, "turn_rate", w.turn_rate, 100.0);
  w.avoid_range = PositiveParam(pnh, "avoid_range", w.avoid_range, 100.0);
  w.slow_range = NumberParam(pnh, "slow_range", w.slow_range, 0.0, 100.0);
  w.heading_change = NumberParam(pnh, "heading_change", w.heading_change, 0.0, 100.0);
  w.heading_period = PositiveParam(pnh, "heading_period", w.heading_period);
  CheckOptionParams(pnh, {"cruise_speed", "turn_rate", "avoid_range", "slow_range", "heading_change", "heading_period"},
                    [&] { behaviours::ValidateOptions(w); });

  // The search for a charger when none is known.
  charging_demo::SearchOptions& se = c.search;
  se.cell = PositiveParam(pnh, "search_cell", se.cell, 100.0);
  se.goal_distance = PositiveParam(pnh, "search_goal_distance", se.goal_distance, 100.0);
  se.directions = IntParam(pnh, "search_directions", se.directions, 1, 3600);
  se.hold = PositiveParam(pnh, "search_hold", se.hold);
  se.unreachable_penalty = NumberParam(pnh, "search_unreachable_penalty", se.unreachable_penalty, 0.0, 1e6);
  // ...and after follow_after s of it, following walls.
  c.follow_after = NumberParam(pnh, "follow_after", c.follow_after, 0.0, 1e6);
  charging_demo::WallFollowOptions& wf = c.wall_follow;
  wf.distance = PositiveParam(pnh, "wall_distance", wf.distance, 100.0);
  wf.speed = PositiveParam(pnh, "wall_speed", wf.speed, 100.0);
  wf.gain = PositiveParam(pnh, "wall_gain", wf.gain, 1000.0);
  wf.turn_rate = PositiveParam(pnh, "wall_turn_rate", wf.turn_rate, 100.0);
  wf.lost_range = PositiveParam(pnh, "wall_lost_range", wf.lost_range, 100.0);
  wf.corner_radius = PositiveParam(pnh, "wall_corner_radius", wf.corner_radius, 100.0);

  c.keep_out = PositiveParam(pnh, "keep_out", c.keep_out, 100.0);
  // Going back along the trail to a charger the local map has lost the way to.
  c.trail.spacing = PositiveParam(pnh, "trail_spacing", c.trail.spacing, 100.0);
  c.trail.capacity = static_cast<std::size_t>(IntParam(pnh, "trail_capacity", static_cast<int>(c.trail.capacity), 2, kMaxInt));
  c.retrace_after = PositiveParam(pnh, "retrace_after", c.retrace_after);
  c.retrace_reach = PositiveParam(pnh, "retrace_reach", c.retrace_reach, 100.0);
  c.seed = static_cast<std::uint32_t>(IntParam(pnh, "seed", static_cast<int>(default_seed & 0x7fffffff), 0, kMaxInt));
  o.control_rate = NumberParam(pnh, "control_rate", o.control_rate, 0.1, 1000.0);
  o.state_rate = NumberParam(pnh, "state_rate", o.state_rate, 0.0, 1000.0);
  try {
    charging_demo::ValidateOptions(c);
  } catch (const std::invalid_argument& error) {
    throw ParamError(pnh.getNamespace() + ": the parameters give impossible charging options: " + error.what());
  }
  return o;
}

ChargingDemoRos::ChargingDemoRos(ros::NodeHandle nh, ros::NodeHandle pnh, const ChargingDemoNodeOptions& options)
    : nh_(nh),
      pnh_(pnh),
      lockstep_(nh),
      options_(options),
      controller_(options.controller) {
  release_ = nh_.serviceClient<std_srvs::Trigger>("local_mutex/release");
  cmd_pub_ = lockstep_.Advertise<geometry_msgs::Twist>(nh_, "cmd_vel", 10);
  state_pub_ = lockstep_.Advertise<multirobot_audio::ChargingState>(pnh_, "state", 10);
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("charger", 1);
  odom_sub_ = guard_.Subscribe<nav_msgs::Odometry>(lockstep_, nh_, "odom", 10, OdometryProblem,
                                                   [this](const nav_msgs::Odometry::ConstPtr& m) { OnOdometry(m); });
  scan_sub_ = guard_.Subscribe<sensor_msgs::LaserScan>(lockstep_, nh_, "scan", 10, ScanProblem,
                                                       [this](const sensor_msgs::LaserScan::ConstPtr& m) { OnScan(m); });
  fiducials_sub_ = guard_.Subscribe<multirobot_audio::FiducialArray>(
      lockstep_, nh_, "fiducials", 10, FiducialsProblem,
      [this](const multirobot_audio::FiducialArray::ConstPtr& m) { OnFiducials(m); });
  battery_sub_ = guard_.Subscribe<sensor_msgs::BatteryState>(
      lockstep_, nh_, "battery", 10, BatteryProblem, [this](const sensor_msgs::BatteryState::ConstPtr& m) { OnBattery(m); });
  lock_sub_ = guard_.Subscribe<multirobot_audio::LockState>(
      lockstep_, nh_, "local_mutex/state", 10, LockStateProblem,
      [this](const multirobot_audio::LockState::ConstPtr& m) { OnLockState(m); });
  // The action client's subscriptions: what the local_mutex (or anyone) says about goals.
  for (const char* topic : {"status", "feedback", "result"}) {
    guard_.Watch(nh_.resolveName(std::string("local_mutex/acquire/") + topic));
  }
  control_timer_ = lockstep_.CreateTimer(nh_, ros::Duration(1.0 / options_.control_rate), &ChargingDemoRos::OnControl, this);
  std::string ids;
  for (const std::uint32_t id : options_.controller.charging.chargers) ids += (ids.empty() ? "" : ", ") + std::to_string(id);
  const charging_demo::ChargingOptions& ch = options_.controller.charging;
  ROS_INFO("charging_demo %s: chargers [%s], charge below %.2f up to %.2f, wait %.2f m off, control at %.1f Hz",
           nh_.getNamespace().c_str(), ids.c_str(), ch.low_battery, ch.full_battery, ch.wait_distance,
           options_.control_rate);
}

ChargingDemoRos::~ChargingDemoRos() {
  const charging_demo::ChargingBehaviour& b = controller_.behaviour();
  // Printed directly: the node's logging is already shut down when it is destroyed.
  std::printf("charging_demo summary: %s phase %s, battery %.2f, charges %lu, give-ups %lu, redocks %lu, "
              "lock goals %lu (granted %lu, cancelled %lu), releases %lu, late updates %lu of %lu; %s\n",
              nh_.getNamespace().c_str(), charging_demo::PhaseName(b.phase()), battery_, Count(b.charges()),
              Count(b.give_ups()), Count(b.redocks()), Count(goals_), Count(grants_), Count(cancels_),
              Count(releases_), Count(late_), Count(updates_), guard_.Summary().c_str());
  std::fflush(stdout);
}

void ChargingDemoRos::OnOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  odom_frame_ = msg->header.frame_id;
  have_odom_ = true;
  controller_.OnOdometry(FromPose(msg->pose.pose), msg->header.stamp.toSec());
}

void ChargingDemoRos::OnScan(const sensor_msgs::LaserScan::ConstPtr& msg) {
  if (!ring_checked_) {
    ring_checked_ = true;
    const std::string problem = RingProblem(*msg);
    if (!problem.empty()) {
      ROS_WARN("charging_demo %s: %s is not a ring of rangers as the controller expects: %s",
               nh_.getNamespace().c_str(), scan_sub_.getTopic().c_str(), problem.c_str());
    }
  }
  controller_.OnRanges(ToRangeReadings(*msg), msg->range_max, msg->header.stamp.toSec());
}

void ChargingDemoRos::OnFiducials(const multirobot_audio::FiducialArray::ConstPtr& msg) {
  controller_.OnSightings(ToChargerSightings(*msg));
}

void ChargingDemoRos::OnBattery(const sensor_msgs::BatteryState::ConstPtr& msg) {
  const BatteryReading r = FromBatteryState(*msg);  // a finite level: BatteryProblem has seen to it
  battery_ = r.level;
  docked_ = r.docked;
  have_battery_ = true;
  controller_.OnBattery(r.level, r.docked);
}

void ChargingDemoRos::SetLock(State state, const ros::Time& stamp, bool own) {
  // Reports arrive in order on each connection, but the state topic, the action and the service
  // are separate connections: a report stamped no later than what the node learnt itself (a
  // grant in a result, its own release) may have been sent before it, and is stale.
  if (!own && stamp <= own_known_) return;
  lock_ = state;
  if (own) own_known_ = stamp;
}

void ChargingDemoRos::OnLockState(const multirobot_audio::LockState::ConstPtr& msg) {
  // A known state: LockStateProblem has seen to it.
  if (const std::optional<State> state = FromLockStateValue(msg->state)) SetLock(*state, msg->header.stamp, false);
}

void ChargingDemoRos::OnGoalFeedback(const multirobot_audio::AcquireLockFeedbackConstPtr& feedback) {
  if (const std::optional<State> state = FromLockStateValue(feedback->state)) SetLock(*state, ros::Time::now(), false);
}

void ChargingDemoRos::OnGoalDone(const actionlib::SimpleClientGoalState& state,
                                 const multirobot_audio::AcquireLockResultConstPtr& result) {
  goal_active_ = false;
  cancel_sent_ = false;
  if (result && result->acquired) {
    ++grants_;
    SetLock(State::kHeld, ros::Time::now(), true);
    ROS_INFO("charging_demo %s: lock granted after %.1f s", nh_.getNamespace().c_str(), result->waited);
  } else if (state != actionlib::SimpleClientGoalState::PREEMPTED) {
    // Not by our cancel: aborted (the local_mutex gave up or went away). FollowLock asks again
    // if the lock is still wanted.
    ROS_WARN("charging_demo %s: lock goal ended %s (%s)", nh_.getNamespace().c_str(), state.toString().c_str(),
             state.getText().c_str());
  }
}

void ChargingDemoRos::FollowLock(bool want, const ros::Time& now) {
  if (want != want_lock_) {
    want_lock_ = want;
    // A fresh change of mind acts at once; only repeats wait kLockRetry.
    last_goal_ = last_release_ = ros::Time();
  }
  if (want) {
    if (lock_ == State::kHeld || goal_active_) return;
    if (!last_goal_.isZero() && (now - last_goal_).toSec() < kLockRetry) return;
    if (!acquire_ || !acquire_->isServerConnected()) {
      ROS_WARN_THROTTLE(10.0, "charging_demo %s: the lock is wanted but %s is not up", nh_.getNamespace().c_str(),
                        nh_.resolveName("local_mutex/acquire").c_str());
      return;
    }
    multirobot_audio::AcquireLockGoal goal;
    goal.timeout = 0.0;  // the behaviour decides when to give up (lock_timeout) and cancels
    acquire_->sendGoal(
        goal,
        [this](const actionlib::SimpleClientGoalState& state, const multirobot_audio::AcquireLockResultConstPtr& result) {
          OnGoalDone(state, result);
        },
        AcquireClient::SimpleActiveCallback(),
        [this](const multirobot_audio::AcquireLockFeedbackConstPtr& feedback) { OnGoalFeedback(feedback); });
    goal_active_ = true;
    cancel_sent_ = false;
    last_goal_ = now;
    ++goals_;
    return;
  }
  if (goal_active_) {
    if (!cancel_sent_) {
      acquire_->cancelGoal();  // withdraws the request; a grant that crossed it is released below
      cancel_sent_ = true;
      ++cancels_;
    }
    return;
  }
  if (lock_ == State::kReleased) return;
  if (!last_release_.isZero() && (now - last_release_).toSec() < kLockRetry) return;
  Release(now);
}

void ChargingDemoRos::Release(const ros::Time& now) {
  last_release_ = now;
  std_srvs::Trigger call;
  if (!release_.call(call)) {
    ROS_WARN_THROTTLE(10.0, "charging_demo %s: %s did not answer", nh_.getNamespace().c_str(),
                      release_.getService().c_str());
    return;
  }
  ++releases_;
  // The local_mutex has let go when it answers; reports from before are stale.
  SetLock(State::kReleased, ros::Time::now(), true);
}

void ChargingDemoRos::OnControl(const ros::TimerEvent& event) {
  const ros::Time now = ros::Time::now();
  if (started_.isZero()) started_ = now;
  if (!acquire_ && ros::Time::isValid()) {
    // No thread of its own: its callbacks run on the node's queue, beside the control loop.
    acquire_ = std::make_unique<AcquireClient>(nh_, "local_mutex/acquire", false);
  }
  if (!have_odom_ || !have_battery_) {
    if ((now - started_).toSec() > kInputsPatience) {
      std::string missing;
      if (!have_odom_) missing += " " + odom_sub_.getTopic();
      if (!have_battery_) missing += " " + battery_sub_.getTopic();
      ROS_WARN_THROTTLE(10.0, "charging_demo %s: standing still, waiting for%s", nh_.getNamespace().c_str(),
                        missing.c_str());
    }
    return;
  }
  // An update more than half a period behind its schedule: the node does not keep up with the
  // simulated clock (too high a real-time factor for the machine).
  if ((now - event.current_expected).toSec() > 0.5 / options_.control_rate) ++late_;
  ++updates_;

  const charging_demo::Phase before = controller_.behaviour().phase();
  const charging_demo::ControllerOutput out = controller_.Update(lock_, now.toSec());
  geometry_msgs::Twist cmd;
  cmd.linear.x = out.v;
  cmd.angular.z = out.w;
  cmd_pub_.publish(cmd);
  FollowLock(out.want_lock, now);

  const charging_demo::Phase phase = controller_.behaviour().phase();
  if (phase != before) {
    ROS_INFO("charging_demo %s: %s -> %s (battery %.2f, lock %s)", nh_.getNamespace().c_str(),
             charging_demo::PhaseName(before), charging_demo::PhaseName(phase), battery_,
             local_mutex::StateName(lock_));
  }
  const bool changed = !state_published_ || phase != last_phase_ || lock_ != last_lock_ ||
                       docked_ != last_docked_ || out.want_lock != last_want_;
  const bool due = options_.state_rate > 0.0 && (now - last_state_).toSec() >= 1.0 / options_.state_rate;
  if (changed || due) PublishState(now);
}

void ChargingDemoRos::PublishState(const ros::Time& now) {
  const charging_demo::ChargingBehaviour& b = controller_.behaviour();
  const ChargingStatus status{lock_, want_lock_, battery_, docked_, controller_.retracing(), controller_.retraces()};
  state_pub_.publish(ToChargingState(b, status, now.toSec(), odom_frame_, now));
  if (markers_pub_.getNumSubscribers() > 0) {
    std::string label = nh_.getNamespace();
    if (!label.empty() && label.front() == '/') label.erase(0, 1);
    markers_pub_.publish(ToChargerMarkers(b, status, options_.controller.charging.wait_distance, label,
                                          controller_.navigator().pose(), odom_frame_, now));
  }
  state_published_ = true;
  last_state_ = now;
  last_phase_ = b.phase();
  last_lock_ = lock_;
  last_docked_ = docked_;
  last_want_ = want_lock_;
}

}  // namespace multirobot_audio
