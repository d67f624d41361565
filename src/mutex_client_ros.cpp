#include "mutex_client_ros.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <std_srvs/Trigger.h>

#include "params.h"

namespace multirobot_audio {

MutexClientOptions ReadMutexClientOptions(const ros::NodeHandle& pnh) {
  MutexClientOptions o;
  o.start_delay = NumberParam(pnh, "start_delay", o.start_delay, 0.0, 1e6);
  o.hold = NumberParam(pnh, "hold", o.hold, 0.0, 1e6);
  o.pause = NumberParam(pnh, "pause", o.pause, 0.0, 1e6);
  o.timeout = NumberParam(pnh, "timeout", o.timeout, 0.0, 1e6);
  o.cycles = IntParam(pnh, "cycles", o.cycles, 0, 1000000);
  return o;
}

// The action client spins a thread of its own, so Run() may block on results and sleeps.
MutexClient::MutexClient(ros::NodeHandle nh, const MutexClientOptions& options)
    : nh_(nh), options_(options), acquire_(nh, "local_mutex/acquire", true) {
  release_ = nh_.serviceClient<std_srvs::Trigger>("local_mutex/release");
  // The action client's subscriptions: what the local_mutex (or anyone) says about goals.
  for (const char* topic : {"status", "feedback", "result"}) {
    guard_.Watch(nh_.resolveName(std::string("local_mutex/acquire/") + topic));
  }
}

MutexClient::~MutexClient() {
  // Printed directly: the node's logging is already shut down when it is destroyed.
  const int waits = grants_ - bad_waits_;
  std::printf("mutex_client summary: grants %d, gave up %d, mean wait %.1f s, longest wait %.1f s, impossible waits "
              "%d; %s\n",
              grants_, give_ups_, waits > 0 ? total_wait_ / waits : 0.0, longest_wait_, bad_waits_,
              guard_.Summary().c_str());
  std::fflush(stdout);
}

void MutexClient::Run() {
  ROS_INFO("mutex_client: waiting for %s", nh_.resolveName("local_mutex/acquire").c_str());
  while (nh_.ok() && !acquire_.waitForServer(ros::Duration(5.0))) {}
  if (!Pause(options_.start_delay)) return;
  for (int cycle = 1; nh_.ok() && (options_.cycles == 0 || cycle <= options_.cycles); ++cycle) {
    if (Acquire(cycle)) {
      if (!Pause(options_.hold)) return;
      Release(cycle);
    }
    if (!Pause(options_.pause)) return;
  }
}

bool MutexClient::Pause(double seconds) {
  // ros::Duration(0).sleep() says false on simulated time (no time passed), which is not a
  // shutdown: a start_delay of 0 must not end the client.
  if (seconds > 0.0) ros::Duration(seconds).sleep();
  return nh_.ok();
}

bool MutexClient::Acquire(int cycle) {
  multirobot_audio::AcquireLockGoal goal;
  goal.timeout = options_.timeout;
  ROS_INFO("mutex_client: cycle %d: asking for the lock", cycle);
  acquire_.sendGoal(goal);
  while (nh_.ok() && !acquire_.waitForResult(ros::Duration(1.0))) {}
  const auto result = acquire_.getResult();
  if (!nh_.ok() || !result) return false;
  if (!result->acquired) {
    ++give_ups_;
    ROS_WARN("mutex_client: cycle %d: no lock after %.1f s (%s)", cycle, result->waited,
             acquire_.getState().getText().c_str());
    return false;
  }
  ++grants_;
  if (std::isfinite(result->waited) && result->waited >= 0.0) {
    total_wait_ += result->waited;
    longest_wait_ = std::max(longest_wait_, result->waited);
  } else {
    // Granted all the same; only the wait is left out of the statistics.
    ++bad_waits_;
    ROS_WARN("mutex_client: cycle %d: the result says it waited %g s; left out of the wait statistics", cycle,
             result->waited);
  }
  ROS_INFO("mutex_client: cycle %d: lock granted after waiting %.1f s; holding it %.1f s", cycle, result->waited,
           options_.hold);
  return true;
}

void MutexClient::Release(int cycle) {
  std_srvs::Trigger release;
  if (!release_.call(release)) {
    ROS_ERROR("mutex_client: cycle %d: %s did not answer", cycle, release_.getService().c_str());
    return;
  }
  ROS_INFO("mutex_client: cycle %d: released (%s)", cycle, release.response.message.c_str());
}

}  // namespace multirobot_audio
