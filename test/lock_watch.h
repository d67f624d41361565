#pragma once
// What the local mutex's rostests share: a watch on every robot's local_mutex/state that
// reconstructs the grants, and a robot's lock used the way a client uses it.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <actionlib/client/simple_action_client.h>
#include <multirobot_audio/AcquireLockAction.h>
#include <multirobot_audio/LockState.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

namespace multirobot_audio::testing {

// One grant, as the robot's LockState messages tell it (times on the ROS clock).
struct Grant {
  std::string robot;
  int robot_id = 0;
  int request_time = 0;  // T_i
  double held_from = 0.0;
  double held_until = 0.0;  // +inf while still held
};

// "robot_2 (3, #212) held 61.2..71.3" per grant, for failure messages.
std::string Describe(const std::vector<Grant>& grants);
// The robots, in the order of `grants`.
std::vector<std::string> Robots(const std::vector<Grant>& grants);
// `grants` sorted by their requests' (T_i, id): the order the lock promises. (The tests' clocks
// stay far below where the 16-bit Lamport time wraps.)
std::vector<Grant> InRequestOrder(std::vector<Grant> grants);

class LockWatch {
 public:
  LockWatch(ros::NodeHandle nh, const std::vector<std::string>& robots);

  // Every robot's local_mutex has published its state.
  bool Ready(double wall_seconds);
  // The robot's latest message (all zeros before the first).
  const LockState& Latest(const std::string& robot) { return latest_[robot]; }
  // The grants since the start or Forget(), in the order they were granted.
  const std::vector<Grant>& Grants() const { return grants_; }
  // Pairs of grants whose HELD times overlap, described; empty when the lock stayed exclusive.
  std::vector<std::string> Overlaps() const;
  // The most robots HELD at once, judged as each message arrived.
  int MostHeldAtOnce() const { return most_held_; }
  // How often the robot entered `state` since the start or Forget().
  int Entries(const std::string& robot, std::uint8_t state) const;
  void Forget();

 private:
  void OnState(const std::string& robot, const LockState& msg);

  std::vector<ros::Subscriber> subs_;
  std::map<std::string, LockState> latest_;
  std::map<std::string, std::map<std::uint8_t, int>> entries_;
  std::vector<Grant> grants_;
  int most_held_ = 0;
};

// A robot's lock seen from a client: the local_mutex/acquire action and local_mutex/release.
// Its callbacks run on the global queue, which WaitFor spins.
class LockUser {
 public:
  LockUser(ros::NodeHandle nh, const std::string& robot);

  const std::string& robot() const { return robot_; }
  bool Ready(double wall_seconds);
  void Acquire(double timeout = 0.0);
  void Cancel() { client_.cancelGoal(); }
  // The last goal has finished (succeeded, aborted or preempted).
  bool Done() const { return client_.getState().isDone(); }
  bool Acquired() const;
  actionlib::SimpleClientGoalState GoalState() const { return client_.getState(); }
  // The last goal's result; waited is -1 before it has one.
  AcquireLockResult Result() const;
  // Calls local_mutex/release; success false when the service did not answer.
  std_srvs::Trigger::Response Release();

 private:
  std::string robot_;
  actionlib::SimpleActionClient<AcquireLockAction> client_;
  ros::ServiceClient release_;
};

// Each user has asked for the lock; whenever one is granted it keeps the lock `hold` s of the
// ROS clock and releases it. True once every user has held and released the lock; false when
// `wall_seconds` pass first or a goal ends without the lock (`failure` says which).
bool HoldAndReleaseEach(const std::vector<LockUser*>& users, double hold, double wall_seconds, std::string* failure);

}  // namespace multirobot_audio::testing
