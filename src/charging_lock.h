#pragma once

#include <cstdint>
#include <memory>

#include <actionlib/client/simple_action_client.h>
#include <multirobot_audio/AcquireLockAction.h>
#include <ros/ros.h>

#include "local_mutex/local_mutex.h"

namespace multirobot_audio {

// The charging robot's lock as the charging_demo node follows it through the local_mutex node's
// interface (the local_mutex/acquire action and the local_mutex/release service, in the robot's
// namespace). When the controller starts to want the lock, one acquire goal is sent that waits
// as long as it takes; when it stops wanting it, a waiting goal is cancelled (the request
// withdrawn) or the held lock released. The state it tells is the latest the local_mutex
// reported (state topic, goal feedback and result).
class ChargingLock {
 public:
  struct Counts {
    std::uint64_t goals = 0, grants = 0, cancels = 0, releases = 0;
  };

  explicit ChargingLock(ros::NodeHandle nh);

  // Makes the action client once ROS time is valid; called at every control update (why not in
  // the constructor: see acquire_).
  void MakeClientOnceTimeValid();
  // A report of the lock's state as of `stamp` (the local_mutex/state topic): ignored when it is
  // no newer than what the node learnt itself.
  void OnReport(local_mutex::State state, const ros::Time& stamp) { SetLock(state, stamp, false); }
  // Moves the robot's lock towards `want`.
  void Follow(bool want, const ros::Time& now);

  local_mutex::State state() const { return lock_; }
  bool wanted() const { return want_lock_; }
  const Counts& counts() const { return counts_; }

 private:
  using AcquireClient = actionlib::SimpleActionClient<multirobot_audio::AcquireLockAction>;

  void OnGoalFeedback(const multirobot_audio::AcquireLockFeedbackConstPtr& feedback);
  void OnGoalDone(const actionlib::SimpleClientGoalState& state,
                  const multirobot_audio::AcquireLockResultConstPtr& result);
  void Release(const ros::Time& now);
  // Takes the lock's state as of `stamp`: `own` when the node learnt it from its own goal's
  // result or its own release, else a report (state topic, feedback) that is ignored when it is
  // no newer than the node's own knowledge.
  void SetLock(local_mutex::State state, const ros::Time& stamp, bool own);

  ros::NodeHandle nh_;
  // Made at the first control update, not in the constructor: actionlib's client waits there
  // for a valid ROS time, and in lockstep world_sim starts the clock only once every
  // participant, this node too, has said hello (which needs the constructor to have returned).
  std::unique_ptr<AcquireClient> acquire_;
  ros::ServiceClient release_;

  // The lock: its latest known state, when the node last learnt it itself; the goal in flight.
  local_mutex::State lock_ = local_mutex::State::kReleased;
  ros::Time own_known_;
  bool goal_active_ = false, cancel_sent_ = false;
  ros::Time last_goal_, last_release_;
  bool want_lock_ = false;
  Counts counts_;
};

}  // namespace multirobot_audio
