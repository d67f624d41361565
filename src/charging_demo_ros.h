#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <multirobot_audio/FiducialArray.h>
#include <multirobot_audio/LockState.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/LaserScan.h>

#include "charging_lock.h"
#include "charging_state_publisher.h"
#include "conversions.h"
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
// local_mutex/release service, the local_mutex/state topic), moved by a ChargingLock towards
// what the controller wants. Publishes ~state (ChargingState) and ~charger (markers for rviz)
// through a ChargingStatePublisher. Everything runs on the node's one callback queue.
class ChargingDemoRos {
 public:
  ChargingDemoRos(ros::NodeHandle nh, ros::NodeHandle pnh, const ChargingDemoNodeOptions& options);
  ~ChargingDemoRos();

 private:
  void OnOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void OnScan(const sensor_msgs::LaserScan::ConstPtr& msg);
  void OnFiducials(const multirobot_audio::FiducialArray::ConstPtr& msg);
  void OnBattery(const sensor_msgs::BatteryState::ConstPtr& msg);
  void OnLockState(const multirobot_audio::LockState::ConstPtr& msg);
  void OnControl(const ros::TimerEvent& event);

  ros::NodeHandle nh_;
  LockstepParticipant lockstep_;  // before what it hands messages and timers to
  InputGuard guard_;              // before the subscriptions whose callbacks it checks
  ChargingDemoNodeOptions options_;
  charging_demo::ChargingController controller_;
  ChargingLock lock_;
  CountedPublisher cmd_pub_;
  ChargingStatePublisher state_publisher_;
  ros::Subscriber odom_sub_, scan_sub_, fiducials_sub_, battery_sub_, lock_sub_;
  ros::Timer control_timer_;

  std::optional<std::string> odom_frame_;  // from the odometry; none before the first
  std::optional<BatteryReading> battery_;  // the latest; none before the first
  ros::Time started_;
  bool ring_checked_ = false;

  std::uint64_t updates_ = 0, late_ = 0;
};

}  // namespace multirobot_audio
