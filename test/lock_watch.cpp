#include "lock_watch.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <set>
#include <tuple>

#include "wait_for.h"

namespace multirobot_audio::testing {

std::string Describe(const std::vector<Grant>& grants) {
  std::string out;
  for (const Grant& g : grants) {
    char line[160];
    std::snprintf(line, sizeof line, "\n  %s (%d, #%d) held %.1f..%.1f", g.robot.c_str(), g.request_time, g.robot_id,
                  g.held_from, g.held_until);
    out += line;
  }
  return out.empty() ? "\n  (no grants)" : out;
}

std::vector<std::string> Robots(const std::vector<Grant>& grants) {
  std::vector<std::string> robots;
  for (const Grant& g : grants) robots.push_back(g.robot);
  return robots;
}

std::vector<Grant> InRequestOrder(std::vector<Grant> grants) {
  std::stable_sort(grants.begin(), grants.end(), [](const Grant& a, const Grant& b) {
    return std::tie(a.request_time, a.robot_id) < std::tie(b.request_time, b.robot_id);
  });
  return grants;
}

LockWatch::LockWatch(ros::NodeHandle nh, const std::vector<std::string>& robots) {
  for (const std::string& robot : robots) {
    subs_.push_back(nh.subscribe<LockState>("/" + robot + "/local_mutex/state", 100,
                                            [this, robot](const LockState::ConstPtr& m) { OnState(robot, *m); }));
  }
}

bool LockWatch::Ready(double wall_seconds) {
  return WaitFor([&] {
    for (const ros::Subscriber& sub : subs_) {
      if (sub.getNumPublishers() == 0) return false;
    }
    return latest_.size() == subs_.size();
  }, wall_seconds);
}

void LockWatch::OnState(const std::string& robot, const LockState& msg) {
  const bool first = latest_.count(robot) == 0;
  const std::uint8_t before = first ? std::uint8_t{LockState::RELEASED} : latest_[robot].state;
  latest_[robot] = msg;
  if (!first && msg.state == before) return;
  ++entries_[robot][msg.state];
  const double t = msg.header.stamp.toSec();
  if (msg.state == LockState::HELD) {
    grants_.push_back({robot, msg.robot_id, msg.request_time, t, std::numeric_limits<double>::infinity()});
  } else if (before == LockState::HELD) {
    for (Grant& g : grants_) {
      if (g.robot == robot && g.held_until > t) g.held_until = t;
    }
  }
  int held = 0;
  for (const auto& [name, state] : latest_) held += state.state == LockState::HELD;
  most_held_ = std::max(most_held_, held);
}

std::vector<std::string> LockWatch::Overlaps() const {
  std::vector<std::string> overlaps;
  for (std::size_t a = 0; a < grants_.size(); ++a) {
    for (std::size_t b = a + 1; b < grants_.size(); ++b) {
      const Grant& x = grants_[a];
      const Grant& y = grants_[b];
      if (x.held_from < y.held_until && y.held_from < x.held_until) {
        overlaps.push_back(x.robot + " and " + y.robot + ":" + Describe({x, y}));
      }
    }
  }
  return overlaps;
}

int LockWatch::Entries(const std::string& robot, std::uint8_t state) const {
  const auto r = entries_.find(robot);
  if (r == entries_.end()) return 0;
  const auto s = r->second.find(state);
  return s == r->second.end() ? 0 : s->second;
}

void LockWatch::Forget() {
  entries_.clear();
  grants_.clear();
  most_held_ = 0;
}

LockUser::LockUser(ros::NodeHandle nh, const std::string& robot)
    : robot_(robot), client_(nh, "/" + robot + "/local_mutex/acquire", false) {
  release_ = nh.serviceClient<std_srvs::Trigger>("/" + robot + "/local_mutex/release");
}

bool LockUser::Ready(double wall_seconds) {
  return WaitFor([&] { return client_.isServerConnected() && release_.exists(); }, wall_seconds);
}

void LockUser::Acquire(double timeout) {
  AcquireLockGoal goal;
  goal.timeout = timeout;
  client_.sendGoal(goal);
}

bool LockUser::Acquired() const {
  return GoalState() == actionlib::SimpleClientGoalState::SUCCEEDED && Result().acquired;
}

AcquireLockResult LockUser::Result() const {
  const auto result = client_.getResult();
  if (result) return *result;
  AcquireLockResult none;
  none.waited = -1.0;
  return none;
}

std_srvs::Trigger::Response LockUser::Release() {
  std_srvs::Trigger call;
  if (!release_.call(call)) {
    call.response.success = false;
    call.response.message = "no answer from " + release_.getService();
  }
  return call.response;
}

bool HoldAndReleaseEach(const std::vector<LockUser*>& users, double hold, double wall_seconds, std::string* failure) {
  std::map<LockUser*, ros::Time> granted;
  std::set<LockUser*> released;
  failure->clear();
  const bool finished = WaitFor([&] {
    for (LockUser* user : users) {
      if (released.count(user) || !user->Done()) continue;
      if (!user->Acquired()) {
        *failure = user->robot() + ": acquire ended " + user->GoalState().toString() + " without the lock";
        return true;
      }
      if (!granted.count(user)) granted[user] = ros::Time::now();
      if (ros::Time::now() - granted[user] < ros::Duration(hold)) continue;
      const std_srvs::Trigger::Response r = user->Release();
      if (!r.success) *failure = user->robot() + ": release failed: " + r.message;
      released.insert(user);
    }
    return released.size() == users.size() || !failure->empty();
  }, wall_seconds);
  if (!finished && failure->empty()) {
    *failure = "only " + std::to_string(released.size()) + " of " + std::to_string(users.size()) +
               " robots held and released the lock in time";
  }
  return failure->empty();
}

}  // namespace multirobot_audio::testing
