#pragma once

#include <string>

#include <ros/ros.h>

#include "charging_conversions.h"
#include "lockstep_participant.h"
#include "charging_demo/charging_controller.h"

namespace multirobot_audio {

// The charging_demo node's ~state (ChargingState, counted for the lockstep) and ~charger
// (markers for rviz, only while someone listens): published at once when the phase, the lock,
// docked or the wish for the lock changed since the last time, and else every 1/`rate` s of ROS
// time (never with `rate` 0).
class ChargingStatePublisher {
 public:
  // Advertises on `pnh`; the markers are labelled with the robot's namespace, `robot_namespace`,
  // and draw the ring at `wait_distance` (m) around the charger in use.
  ChargingStatePublisher(LockstepParticipant& lockstep, ros::NodeHandle pnh, double rate, double wait_distance,
                         const std::string& robot_namespace);

  // After a control update at `now`: publishes when it changed or is due. `odom_frame` is the
  // frame the controller's poses are in.
  void Update(const charging_demo::ChargingController& controller, const ChargingStatus& status,
              const std::string& odom_frame, const ros::Time& now);

 private:
  CountedPublisher state_pub_;
  ros::Publisher markers_pub_;  // for rviz only
  double rate_, wait_distance_;
  std::string label_;

  // What ~state last said, to publish again at once on a change.
  charging_demo::Phase last_phase_ = charging_demo::Phase::kDuty;
  local_mutex::State last_lock_ = local_mutex::State::kReleased;
  bool last_docked_ = false, last_want_ = false, published_ = false;
  ros::Time last_time_;
};

}  // namespace multirobot_audio
