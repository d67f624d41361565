#include "charging_demo_ros.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <geometry_msgs/Twist.h>

#include "charging_conversions.h"
#include "input_checks.h"
#include "navigation_conversions.h"
#include "navigation_params.h"
#include "params.h"

namespace multirobot_audio {
namespace {

constexpr int kMaxInt = std::numeric_limits<int>::max();
constexpr double kBig = 1e6;
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
      lockstep_(nh),
      options_(options),
      controller_(options.controller),
      lock_(nh),
      cmd_pub_(lockstep_.Advertise<geometry_msgs::Twist>(nh_, "cmd_vel", 10)),
      state_publisher_(lockstep_, pnh, options.state_rate, options.controller.charging.wait_distance,
                       nh.getNamespace()) {
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
  const ChargingLock::Counts& lock = lock_.counts();
  // Printed directly: the node's logging is already shut down when it is destroyed.
  std::printf("charging_demo summary: %s phase %s, battery %.2f, charges %lu, give-ups %lu, redocks %lu, "
              "lock goals %lu (granted %lu, cancelled %lu), releases %lu, late updates %lu of %lu; %s\n",
              nh_.getNamespace().c_str(), charging_demo::PhaseName(b.phase()), battery_ ? battery_->level : 0.0,
              Count(b.charges()), Count(b.give_ups()), Count(b.redocks()), Count(lock.goals), Count(lock.grants),
              Count(lock.cancels), Count(lock.releases), Count(late_), Count(updates_), guard_.Summary().c_str());
  std::fflush(stdout);
}

void ChargingDemoRos::OnOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  odom_frame_ = msg->header.frame_id;
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
  battery_ = FromBatteryState(*msg);  // a finite level: BatteryProblem has seen to it
  controller_.OnBattery(battery_->level, battery_->docked);
}

void ChargingDemoRos::OnLockState(const multirobot_audio::LockState::ConstPtr& msg) {
  // A known state: LockStateProblem has seen to it.
  if (const std::optional<local_mutex::State> state = FromLockStateValue(msg->state)) {
    lock_.OnReport(*state, msg->header.stamp);
  }
}

void ChargingDemoRos::OnControl(const ros::TimerEvent& event) {
  const ros::Time now = ros::Time::now();
  if (started_.isZero()) started_ = now;
  lock_.MakeClientOnceTimeValid();
  if (!odom_frame_ || !battery_) {
    if ((now - started_).toSec() > kInputsPatience) {
      std::string missing;
      if (!odom_frame_) missing += " " + odom_sub_.getTopic();
      if (!battery_) missing += " " + battery_sub_.getTopic();
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
  const charging_demo::ControllerOutput out = controller_.Update(lock_.state(), now.toSec());
  geometry_msgs::Twist cmd;
  cmd.linear.x = out.v;
  cmd.angular.z = out.w;
  cmd_pub_.publish(cmd);
  lock_.Follow(out.want_lock, now);

  const charging_demo::Phase phase = controller_.behaviour().phase();
  if (phase != before) {
    ROS_INFO("charging_demo %s: %s -> %s (battery %.2f, lock %s)", nh_.getNamespace().c_str(),
             charging_demo::PhaseName(before), charging_demo::PhaseName(phase), battery_->level,
             local_mutex::StateName(lock_.state()));
  }
  const ChargingStatus status{lock_.state(), lock_.wanted(), battery_->level, battery_->docked,
                              controller_.retracing(), controller_.retraces()};
  state_publisher_.Update(controller_, status, *odom_frame_, now);
}

}  // namespace multirobot_audio
