#pragma once

#include <actionlib/client/simple_action_client.h>
#include <multirobot_audio/AcquireLockAction.h>
#include <ros/ros.h>

#include "input_guard.h"

namespace multirobot_audio {

// What the mutex_client does, from its private parameters (s of the robot's clock).
struct MutexClientOptions {
  double start_delay = 0.0;  // ~start_delay: before the first acquire
  double hold = 20.0;        // ~hold: how long the lock is kept
  double pause = 30.0;       // ~pause: after a release (or a give-up), before asking again
  double timeout = 0.0;      // ~timeout: of each acquire; 0 = wait forever
  int cycles = 0;            // ~cycles: acquire-hold-release rounds; 0 = until shutdown
};

MutexClientOptions ReadMutexClientOptions(const ros::NodeHandle& pnh);

// A small user of the robot's local mutex, for demonstrations and trials: acquires through
// local_mutex/acquire, holds, releases through local_mutex/release, pauses, and again. Runs in
// the robot's namespace. Its guard's timers run on the global callback queue: the node must spin
// it (an AsyncSpinner beside Run()).
class MutexClient {
 public:
  MutexClient(ros::NodeHandle nh, const MutexClientOptions& options);
  ~MutexClient();

  // Blocks until the cycles are done or the node shuts down.
  void Run();

 private:
  // Sleeps `seconds` of ROS time; false when the node is shutting down.
  bool Pause(double seconds);
  // True when the lock was granted.
  bool Acquire(int cycle);
  void Release(int cycle);

  ros::NodeHandle nh_;
  MutexClientOptions options_;
  InputGuard guard_;
  actionlib::SimpleActionClient<multirobot_audio::AcquireLockAction> acquire_;
  ros::ServiceClient release_;
  int grants_ = 0, give_ups_ = 0, bad_waits_ = 0;  // bad: a result's wait not a finite s
  double total_wait_ = 0.0, longest_wait_ = 0.0;
};

}  // namespace multirobot_audio
