// rostest for the local_mutex node on the simulated audio channel (test/local_mutex.test): the
// test plays the clients of robot_0 (#11), robot_1 (#30) and robot_2 (#212). The tests run in
// order and share the robots; each leaves every lock RELEASED.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "lock_watch.h"
#include "wait_for.h"

namespace multirobot_audio::testing {
namespace {

using actionlib::SimpleClientGoalState;

const std::vector<std::string> kRobots = {"robot_0", "robot_1", "robot_2"};
// s of simulated time each client keeps the lock.
constexpr double kHold = 10.0;
// Wall seconds for one robot to get a free lock: 40 s of silence after up to ~20 s until its
// first request, at 10x real time, with room for a slow machine.
constexpr double kGrantWall = 60.0;

// Spins callbacks for `seconds` of the ROS clock.
void SleepRos(double seconds) {
  const ros::Time end = ros::Time::now() + ros::Duration(seconds);
  WaitFor([&] { return ros::Time::now() >= end; }, seconds + 30.0);
}

class LocalMutexNode : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ros::NodeHandle nh;
    watch_ = new LockWatch(nh, kRobots);
    for (const std::string& robot : kRobots) users_[robot] = std::make_unique<LockUser>(nh, robot);
  }
  static void TearDownTestSuite() {
    users_.clear();
    delete watch_;
  }
  void SetUp() override {
    ASSERT_TRUE(watch_->Ready(60.0)) << "the local_mutex nodes did not come up";
    for (auto& [robot, user] : users_) ASSERT_TRUE(user->Ready(30.0)) << robot << ": no acquire action or release service";
    watch_->Forget();
  }
  static LockUser& User(const std::string& robot) { return *users_[robot]; }
  // Asks for robot's lock and waits until it holds it.
  static bool Hold(const std::string& robot) {
    User(robot).Acquire();
    return WaitFor([&] { return User(robot).Done(); }, kGrantWall) && User(robot).Acquired();
  }

  static LockWatch* watch_;
  static std::map<std::string, std::unique_ptr<LockUser>> users_;
};
LockWatch* LocalMutexNode::watch_ = nullptr;
std::map<std::string, std::unique_ptr<LockUser>> LocalMutexNode::users_;

TEST_F(LocalMutexNode, GrantsFollowTheRequestOrderAndNeverOverlap) {
  // robot_2 (#212) asks first. #11 and #30 ask together once its request is on the air (a packet
  // lasts 0.37 s), so their request times are later: the earlier time outranks the smaller id,
  // and the id breaks the tie between #11 and #30. (Waiting on what robot_2 sent, not on what
  // the others heard, lets the test go on, and fail, when they do not hear.)
  User("robot_2").Acquire();
  ASSERT_TRUE(WaitFor([&] { return watch_->Latest("robot_2").sent > 0; }, kGrantWall)) << "robot_2 did not ask";
  SleepRos(2.0);
  User("robot_0").Acquire();
  User("robot_1").Acquire();

  std::string failure;
  EXPECT_TRUE(HoldAndReleaseEach({&User("robot_0"), &User("robot_1"), &User("robot_2")}, kHold, 3 * kGrantWall,
                                 &failure)) << failure << Describe(watch_->Grants());

  const std::vector<Grant>& grants = watch_->Grants();
  EXPECT_TRUE(watch_->Overlaps().empty()) << "two robots held the lock at once:" << Describe(grants);
  EXPECT_EQ(watch_->MostHeldAtOnce(), 1);
  ASSERT_EQ(grants.size(), 3u) << Describe(grants);
  EXPECT_EQ(Robots(grants), Robots(InRequestOrder(grants))) << "grants out of request order:" << Describe(grants);
  EXPECT_EQ(Robots(grants), std::vector<std::string>({"robot_2", "robot_0", "robot_1"})) << Describe(grants);
  EXPECT_LT(grants[0].request_time, grants[1].request_time) << Describe(grants);
  for (const Grant& g : grants) {
    EXPECT_GE(g.held_until - g.held_from, kHold - 0.5) << g.robot << " lost the lock early";
  }
}

TEST_F(LocalMutexNode, ASecondGoalTakesOverTheWaitingRequestAndAGoalWhileHeldSucceedsAtOnce) {
  LockUser other_client(ros::NodeHandle(), "robot_0");
  ASSERT_TRUE(other_client.Ready(30.0));
  User("robot_0").Acquire();
  ASSERT_TRUE(WaitFor([&] { return watch_->Latest("robot_0").state != LockState::RELEASED; }, 10.0));
  const int request_time = watch_->Latest("robot_0").request_time;
  SleepRos(5.0);
  other_client.Acquire();
  ASSERT_TRUE(WaitFor([&] { return other_client.Done(); }, kGrantWall));
  EXPECT_TRUE(other_client.Acquired()) << other_client.GoalState().toString();
  EXPECT_GT(other_client.Result().waited, 0.0);
  EXPECT_EQ(User("robot_0").GoalState(), SimpleClientGoalState::PREEMPTED);
  EXPECT_EQ(watch_->Entries("robot_0", LockState::RELEASED), 0) << "the request was withdrawn";
  ASSERT_EQ(watch_->Grants().size(), 1u) << Describe(watch_->Grants());
  EXPECT_EQ(watch_->Grants()[0].request_time, request_time) << "the request was made anew";

  User("robot_0").Acquire();
  ASSERT_TRUE(WaitFor([&] { return User("robot_0").Done(); }, 5.0)) << "a goal while HELD waited";
  EXPECT_TRUE(User("robot_0").Acquired());
  EXPECT_EQ(User("robot_0").Result().waited, 0.0);

  const std_srvs::Trigger::Response released = User("robot_0").Release();
  EXPECT_TRUE(released.success);
  EXPECT_EQ(released.message, "released");
  EXPECT_TRUE(WaitFor([&] { return watch_->Latest("robot_0").state == LockState::RELEASED; }, 5.0));
}

TEST_F(LocalMutexNode, AGoalThatCannotBeMetInTimeIsAbortedAndACancelWithdrawsTheRequest) {
  ASSERT_TRUE(Hold("robot_0"));

  // robot_1 cannot grab while robot_0 announces its lock every ~10 s.
  const double timeout = 15.0;
  User("robot_1").Acquire(timeout);
  ASSERT_TRUE(WaitFor([&] { return User("robot_1").Done(); }, timeout + 30.0));
  EXPECT_EQ(User("robot_1").GoalState(), SimpleClientGoalState::ABORTED);
  EXPECT_FALSE(User("robot_1").Result().acquired);
  EXPECT_NEAR(User("robot_1").Result().waited, timeout, 0.5);

  User("robot_2").Acquire();
  ASSERT_TRUE(WaitFor([&] { return watch_->Latest("robot_2").state != LockState::RELEASED; }, 10.0));
  SleepRos(3.0);
  User("robot_2").Cancel();
  ASSERT_TRUE(WaitFor([&] { return User("robot_2").Done(); }, 10.0));
  EXPECT_EQ(User("robot_2").GoalState(), SimpleClientGoalState::PREEMPTED);
  EXPECT_FALSE(User("robot_2").Result().acquired);

  // Both gave up their requests: neither takes the lock later, and robot_0 kept it throughout.
  SleepRos(2.0);
  EXPECT_EQ(watch_->Latest("robot_1").state, LockState::RELEASED);
  EXPECT_EQ(watch_->Latest("robot_2").state, LockState::RELEASED);
  EXPECT_EQ(watch_->Latest("robot_0").state, LockState::HELD);
  EXPECT_EQ(watch_->Entries("robot_0", LockState::RELEASED), 0);
  EXPECT_TRUE(User("robot_0").Release().success);
}

TEST_F(LocalMutexNode, ReleaseWhileReleasedSucceedsAndSaysTheLockWasNotHeld) {
  const std_srvs::Trigger::Response r = User("robot_1").Release();
  EXPECT_TRUE(r.success);
  EXPECT_NE(r.message.find("not held"), std::string::npos) << r.message;
  EXPECT_EQ(watch_->Latest("robot_1").state, LockState::RELEASED);
}

}  // namespace
}  // namespace multirobot_audio::testing
