#pragma once

#include <actionlib/server/simple_action_server.h>
#include <multirobot_audio/AcquireLockAction.h>
#include <multirobot_audio/AudioReception.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "input_guard.h"
#include "lockstep_participant.h"
#include "local_mutex/local_mutex.h"

namespace multirobot_audio {

// Options of the local_mutex node, filled from its private parameters.
struct LocalMutexNodeOptions {
  local_mutex::MutexOptions mutex;  // ~robot_id (required), the timers, ~echo_window, ~seed
  double state_rate = 1.0;          // ~state_rate: Hz of local_mutex/state besides every event
};

// Throws ParamError for a missing or mistyped parameter, and std::invalid_argument (naming the
// option) for timers that cannot work together (see local_mutex::ValidateMutexOptions).
LocalMutexNodeOptions ReadLocalMutexNodeOptions(const ros::NodeHandle& pnh);

// One robot's local mutex (thesis chapter 7) on the robot's audio link. Runs in the robot's
// namespace and talks only to audio/tx and audio/rx, so it runs unchanged over
// audio_propagation in simulation and nava_modem on a robot. Serves local_mutex/acquire
// (AcquireLock action), local_mutex/release (std_srvs/Trigger) and publishes local_mutex/state.
// Time is ros::Time (simulated time under /use_sim_time). Everything runs on the node's one
// callback queue, so the lock needs no mutex of its own.
class LocalMutexRos {
 public:
  LocalMutexRos(ros::NodeHandle nh, const LocalMutexNodeOptions& options);
  ~LocalMutexRos();

 private:
  using AcquireServer = actionlib::SimpleActionServer<multirobot_audio::AcquireLockAction>;

  void OnRx(const multirobot_audio::AudioReception::ConstPtr& msg);
  void OnTick(const ros::TimerEvent&);
  void OnEvent(const local_mutex::MutexEvent& event);
  void OnGoal();
  void OnPreempt();
  bool OnRelease(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);

  // Brings the active goal up to date with the lock after anything that may have moved it:
  // succeeds, aborts on a withdrawn request or a timeout, or sends feedback.
  void ServeGoal(double now);
  multirobot_audio::AcquireLockResult GoalResult(bool acquired, double now) const;
  void PublishState();

  ros::NodeHandle nh_;
  LockstepParticipant lockstep_;  // before what it hands messages and timers to
  InputGuard guard_;              // before the subscriptions whose callbacks it checks
  LocalMutexNodeOptions options_;
  local_mutex::LocalMutex lock_;
  local_mutex::State last_state_ = local_mutex::State::kReleased;
  double state_since_ = 0.0;  // when last_state_ was entered (the node's start for the first)
  CountedPublisher tx_pub_, state_pub_;
  ros::Subscriber rx_sub_;
  ros::ServiceServer release_srv_;
  ros::Timer tick_timer_, state_timer_;
  AcquireServer acquire_server_;

  // The active goal: when it was accepted, how long it may wait, when feedback last went out.
  double goal_since_ = 0.0, goal_timeout_ = 0.0, last_feedback_ = 0.0;
  bool feedback_due_ = false;  // the lock moved since the last feedback
};

}  // namespace multirobot_audio
