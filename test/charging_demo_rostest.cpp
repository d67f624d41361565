// rostest for the charging robots (test/charging_demo.test): three charging_demo controllers,
// each with its local_mutex, share one charger in the test room. Every robot must dock and
// charge in turn: each reaches the phase "charge", never two are docked at once (world_sim's
// battery topics say who is docked), and a robot is docked only while its lock is HELD.
// Everything is subscribed before the first test so that nothing early is missed.
#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <multirobot_audio/ChargingState.h>
#include <multirobot_audio/LockState.h>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>

#include "lock_watch.h"
#include "wait_for.h"

namespace multirobot_audio::testing {
namespace {

const std::vector<std::string> kRobots = {"robot_0", "robot_1", "robot_2"};

struct RobotWatch {
  std::vector<std::string> phases;  // every phase entered, in order
  double first_charge = -1.0;       // s of simulated time when the phase "charge" first came
  ChargingState latest;
  int states = 0;
  bool docked = false;              // by the latest battery message
  double docked_since = -1.0;
  std::vector<std::pair<double, double>> dockings;  // (from, to) by the battery messages
};

class ChargingTeam : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ros::NodeHandle nh, pnh("~");
    pnh.param("sim_limit", sim_limit_, sim_limit_);
    pnh.param("wall_limit", wall_limit_, wall_limit_);
    lock_watch_ = new LockWatch(nh, kRobots);
    for (const std::string& robot : kRobots) {
      subs_.push_back(nh.subscribe<ChargingState>("/" + robot + "/charging_demo/state", 100,
                                                  [robot](const ChargingState::ConstPtr& m) { OnState(robot, *m); }));
      subs_.push_back(nh.subscribe<sensor_msgs::BatteryState>(
          "/" + robot + "/battery", 100, [robot](const sensor_msgs::BatteryState::ConstPtr& m) { OnBattery(robot, *m); }));
    }
  }
  static void TearDownTestSuite() {
    subs_.clear();
    delete lock_watch_;
  }

  static void OnState(const std::string& robot, const ChargingState& m) {
    RobotWatch& w = watch_[robot];
    ++w.states;
    if (w.phases.empty() || w.phases.back() != m.phase) w.phases.push_back(m.phase);
    if (m.phase == "charge" && w.first_charge < 0.0) w.first_charge = m.header.stamp.toSec();
    w.latest = m;
  }

  static void OnBattery(const std::string& robot, const sensor_msgs::BatteryState& m) {
    const bool docked = m.power_supply_status == sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_CHARGING ||
                        m.power_supply_status == sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_FULL;
    RobotWatch& w = watch_[robot];
    const double t = m.header.stamp.toSec();
    if (docked && !w.docked) w.docked_since = t;
    if (!docked && w.docked) w.dockings.emplace_back(w.docked_since, t);
    w.docked = docked;
    int docked_now = 0;
    for (const auto& [name, other] : watch_) docked_now += other.docked ? 1 : 0;
    most_docked_ = std::max(most_docked_, docked_now);
    if (docked_now > 1) {
      std::ostringstream s;
      s << t << " s:";
      for (const auto& [name, other] : watch_)
        if (other.docked) s << " " << name;
      double_dockings_.push_back(s.str());
    }
    // The robot docks only once its lock is HELD and lets go only after it has backed off the
    // charger, seconds of driving either side: a dock seen without the lock is a violation.
    if (docked && lock_watch_->Latest(robot).state != LockState::HELD) {
      std::ostringstream s;
      s << robot << " docked at " << t << " s with its lock in state "
        << static_cast<int>(lock_watch_->Latest(robot).state);
      unlocked_dockings_.push_back(s.str());
    }
  }

  static std::string Report() {
    std::ostringstream s;
    s << "at " << ros::Time::now().toSec() << " s of simulated time:";
    for (const auto& [robot, w] : watch_) {
      s << "\n  " << robot << ": " << w.states << " states, battery " << w.latest.battery << ", phases";
      for (const std::string& p : w.phases) s << " " << p;
      s << "; charges " << w.latest.charges << ", give-ups " << w.latest.give_ups << ", known chargers "
        << w.latest.known_chargers << "; docked";
      for (const auto& [from, to] : w.dockings) s << " " << from << ".." << to;
      if (w.docked) s << " " << w.docked_since << "..";
    }
    s << "\n  grants: " << Describe(lock_watch_->Grants());
    return s.str();
  }

  static bool AllCharged() {
    return std::all_of(kRobots.begin(), kRobots.end(), [](const std::string& r) {
      const auto it = watch_.find(r);
      return it != watch_.end() && it->second.first_charge >= 0.0;
    });
  }

  static std::map<std::string, RobotWatch> watch_;
  static std::vector<ros::Subscriber> subs_;
  static LockWatch* lock_watch_;
  static int most_docked_;
  static std::vector<std::string> double_dockings_, unlocked_dockings_;
  // Simulated seconds by which all three must have charged: some 40 s to take a free lock, 70 s
  // of charging, and the drive in and out, per robot; wall seconds allowed for that at 10x.
  static double sim_limit_, wall_limit_;
};
std::map<std::string, RobotWatch> ChargingTeam::watch_;
std::vector<ros::Subscriber> ChargingTeam::subs_;
LockWatch* ChargingTeam::lock_watch_ = nullptr;
int ChargingTeam::most_docked_ = 0;
std::vector<std::string> ChargingTeam::double_dockings_, ChargingTeam::unlocked_dockings_;
double ChargingTeam::sim_limit_ = 1200.0;
double ChargingTeam::wall_limit_ = 200.0;

TEST_F(ChargingTeam, EveryRobotReportsItsStateAndStartsOnItsWay) {
  // Their batteries start below the threshold: each soon looks for (and sees) the charger.
  ASSERT_TRUE(WaitFor(
      [] {
        for (const std::string& robot : kRobots) {
          const auto it = watch_.find(robot);
          if (it == watch_.end() || it->second.latest.known_chargers < 1) return false;
        }
        return true;
      },
      60.0))
      << Report();
  for (const std::string& robot : kRobots) {
    SCOPED_TRACE(robot);
    const ChargingState& s = watch_[robot].latest;
    EXPECT_EQ(s.header.frame_id, robot + "/odom");
    EXPECT_LT(s.battery, 0.3f);
    EXPECT_NE(s.phase, "duty");
  }
}

TEST_F(ChargingTeam, EachRobotDocksAndChargesInTurn) {
  WaitFor([] { return AllCharged() || ros::Time::now().toSec() > sim_limit_; }, wall_limit_);
  ASSERT_TRUE(AllCharged()) << "not every robot reached the phase charge; " << Report();
  // Let the last one settle on its charger for a moment, still watching.
  const ros::Time end = ros::Time::now() + ros::Duration(5.0);
  WaitFor([&] { return ros::Time::now() >= end; }, 10.0);

  EXPECT_EQ(most_docked_, 1) << Report();
  for (const std::string& d : double_dockings_) ADD_FAILURE() << "two robots docked at once at " << d;
  for (const std::string& d : unlocked_dockings_) ADD_FAILURE() << d;
  EXPECT_TRUE(lock_watch_->Overlaps().empty()) << "the lock was HELD by two robots at once; " << Report();

  // In turn: each robot's first docking ended before the next one's began.
  std::vector<std::pair<double, std::string>> firsts;
  for (const std::string& robot : kRobots) firsts.emplace_back(watch_[robot].first_charge, robot);
  std::sort(firsts.begin(), firsts.end());
  for (std::size_t k = 1; k < firsts.size(); ++k) {
    const RobotWatch& before = watch_[firsts[k - 1].second];
    ASSERT_FALSE(before.dockings.empty())
        << firsts[k - 1].second << " was still docked when " << firsts[k].second << " charged; " << Report();
    EXPECT_LE(before.dockings.front().second, firsts[k].first) << Report();
  }
  for (const std::string& robot : kRobots) {
    SCOPED_TRACE(robot);
    const std::vector<std::string>& p = watch_[robot].phases;
    // Each charge came the documented way: waited for the lock, docked with it, charged.
    const auto charge = std::find(p.begin(), p.end(), "charge");
    ASSERT_NE(charge, p.end());
    EXPECT_NE(std::find(p.begin(), charge, "wait"), charge) << Report();
    EXPECT_NE(std::find(p.begin(), charge, "dock"), charge) << Report();
  }
  std::printf("%s\n", Report().c_str());  // for the test log
}

}  // namespace
}  // namespace multirobot_audio::testing
