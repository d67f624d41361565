#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <actionlib/client/simple_action_client.h>
#include <multirobot_audio/AcquireLockAction.h>
#include <multirobot_audio/FiducialArray.h>
#include <multirobot_audio/LockState.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/LaserScan.h>

#include "charging_conversions.h"
#include "input_guard.h"
#include "lockstep_participant.h"
#include "charging_demo/charging_controller.h"

namespace multirobot_audio {

// Options of the charging_demo node, filled from its private parameters.
struct ChargingDemoNodeOptions {
  charging_demo::ControllerOptions controller;
  double control_rate = 10.0;  // ~control_rate: Hz of ROS time between controller updates
  double state_rate = 2.0;     // ~state_rate: Hz of ~state (and ~charger) besides every change
};

// Throws ParamError naming the parameter: ~chargers missing or empty, a threshold outside
// (0, 1), a mistyped or out-of-range value, or options the controller cannot work with
// (charging_demo::ValidateOptions names the field, which is the parameter's name).
// `default_seed` is used when ~seed is unset.
ChargingDemoNodeOptions ReadChargingDemoNodeOptions(const ros::NodeHandle& pnh, std::uint32_t default_seed);

// One charging robot (thesis section 7.2) around the ROS-free charging_demo::ChargingController,
// in the robot's namespace: odom, scan, fiducials and battery in, cmd_vel out, and the robot's
// local mutex through the local_mutex node's interface (the local_mutex/acquire action, the
// local_mutex/release service, the local_mutex/state topic). When the controller starts to
// want the lock it sends one acquire goal that waits as long as it takes; when it stops wanting
// it, a waiting goal is cancelled (the request withdrawn) or the held lock released. The lock
// state the controller is told is the latest the local_mutex reported (state topic, goal
// feedback and result). Publishes ~state (ChargingState) and ~charger (markers for rviz).
// Everything runs on the node's one callback queue.
class ChargingDemoRos {
 public:
  ChargingDemoRos(ros::NodeHandle nh, ros::NodeHandle pnh, const ChargingDemoNodeOptions& options);
  ~ChargingDemoRos();

 private:
  using AcquireClient = actionlib::SimpleActionClient<multirobot_audio::AcquireLockAction>;

  void OnOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void OnScan(const sensor_msgs::LaserScan::ConstPtr& msg);
  void OnFiducials(const multirobot_audio::FiducialArray::ConstPtr& msg);
  void OnBattery(const sensor_msgs::BatteryState::ConstPtr& msg);
  void OnLockState(const multirobot_audio::LockState::ConstPtr& msg);
  void OnGoalFeedback(const multirobot_audio::AcquireLockFeedbackConstPtr& feedback);
  void OnGoalDone(const actionlib::SimpleClientGoalState& state,
                  const multirobot_audio::AcquireLockResultConstPtr& result);
  void OnControl(const ros::TimerEvent& event);

  // Moves the robot's lock towards what the controller wants.
  void FollowLock(bool want, const ros::Time& now);
  void Release(const ros::Time& now);
  // Takes the lock's state as of `stamp`: `own` when the node learnt it from its own goal's
  // result or its own release, else a report (state topic, feedback) that is ignored when it is
  // no newer than the node's own knowledge.
  void SetLock(local_mutex::State state, const ros::Time& stamp, bool own);
  void PublishState(const ros::Time& now);

  ros::NodeHandle nh_, pnh_;
  LockstepParticipant lockstep_;  // before what it hands messages and timers to
  InputGuard guard_;              // before the subscriptions whose callbacks it checks
  ChargingDemoNodeOptions options_;
  charging_demo::ChargingController controller_;
  // Made at the first control update, not in the constructor: actionlib's client waits there
  // for a valid ROS time, and in lockstep world_sim starts the clock only once every
  // participant, this node too, has said hello (which needs the constructor to have returned).
  std::unique_ptr<AcquireClient> acquire_;
  ros::ServiceClient release_;
  ros::Subscriber odom_sub_, scan_sub_, fiducials_sub_, battery_sub_, lock_sub_;
  CountedPublisher cmd_pub_, state_pub_;
  ros::Publisher markers_pub_;  // for rviz only
  ros::Timer control_timer_;

  std::string odom_frame_;  // from the odometry
  bool have_odom_ = false, have_battery_ = false;
  ros::Time started_;
  double battery_ = 0.0;
  bool docked_ = false;

  // The lock: its latest known state, when the node last learnt it itself; the goal in flight.
  local_mutex::State lock_ = local_mutex::State::kReleased;
  ros::Time own_known_;
  bool goal_active_ = false, cancel_sent_ = false;
  ros::Time last_goal_, last_release_;
  bool want_lock_ = false;

  // What ~state last said, to publish again at once on a change.
  charging_demo::Phase last_phase_ = charging_demo::Phase::kDuty;
  local_mutex::State last_lock_ = local_mutex::State::kReleased;
  bool last_docked_ = false, last_want_ = false, state_published_ = false;
  ros::Time last_state_;
  bool ring_checked_ = false;

  std::uint64_t updates_ = 0, late_ = 0, goals_ = 0, cancels_ = 0, releases_ = 0, grants_ = 0;
};

}  // namespace multirobot_audio
