#include "charging_lock.h"

#include <optional>

#include <std_srvs/Trigger.h>

#include "charging_conversions.h"

namespace multirobot_audio {
namespace {

using local_mutex::State;

// s of ROS time between repeats of a lock command that has not shown its effect yet (a goal
// for a lock that is still not HELD, a release for one that is still not RELEASED).
constexpr double kLockRetry = 2.0;

}  // namespace

ChargingLock::ChargingLock(ros::NodeHandle nh) : nh_(nh) {
  release_ = nh_.serviceClient<std_srvs::Trigger>("local_mutex/release");
}

void ChargingLock::MakeClientOnceTimeValid() {
  if (!acquire_ && ros::Time::isValid()) {
    // No thread of its own: its callbacks run on the node's queue, beside the control loop.
    acquire_ = std::make_unique<AcquireClient>(nh_, "local_mutex/acquire", false);
  }
}

void ChargingLock::SetLock(State state, const ros::Time& stamp, bool own) {
  // Reports arrive in order on each connection, but the state topic, the action and the service
  // are separate connections: a report stamped no later than what the node learnt itself (a
  // grant in a result, its own release) may have been sent before it, and is stale.
  if (!own && stamp <= own_known_) return;
  lock_ = state;
  if (own) own_known_ = stamp;
}

void ChargingLock::OnGoalFeedback(const multirobot_audio::AcquireLockFeedbackConstPtr& feedback) {
  if (const std::optional<State> state = FromLockStateValue(feedback->state)) SetLock(*state, ros::Time::now(), false);
}

void ChargingLock::OnGoalDone(const actionlib::SimpleClientGoalState& state,
                              const multirobot_audio::AcquireLockResultConstPtr& result) {
  goal_active_ = false;
  cancel_sent_ = false;
  if (result && result->acquired) {
    ++counts_.grants;
    SetLock(State::kHeld, ros::Time::now(), true);
    ROS_INFO("charging_demo %s: lock granted after %.1f s", nh_.getNamespace().c_str(), result->waited);
  } else if (state != actionlib::SimpleClientGoalState::PREEMPTED) {
    // Not by our cancel: aborted (the local_mutex gave up or went away). Follow asks again if
    // the lock is still wanted.
    ROS_WARN("charging_demo %s: lock goal ended %s (%s)", nh_.getNamespace().c_str(), state.toString().c_str(),
             state.getText().c_str());
  }
}

void ChargingLock::Follow(bool want, const ros::Time& now) {
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
    ++counts_.goals;
    return;
  }
  if (goal_active_) {
    if (!cancel_sent_) {
      acquire_->cancelGoal();  // withdraws the request; a grant that crossed it is released below
      cancel_sent_ = true;
      ++counts_.cancels;
    }
    return;
  }
  if (lock_ == State::kReleased) return;
  if (!last_release_.isZero() && (now - last_release_).toSec() < kLockRetry) return;
  Release(now);
}

void ChargingLock::Release(const ros::Time& now) {
  last_release_ = now;
  std_srvs::Trigger call;
  if (!release_.call(call)) {
    ROS_WARN_THROTTLE(10.0, "charging_demo %s: %s did not answer", nh_.getNamespace().c_str(),
                      release_.getService().c_str());
    return;
  }
  ++counts_.releases;
  // The local_mutex has let go when it answers; reports from before are stale.
  SetLock(State::kReleased, ros::Time::now(), true);
}

}  // namespace multirobot_audio
