// The local mutex over real sound: three robots' local_mutex nodes talking through nava_modem
// links on one PulseAudio null sink (test/mutex_air.test, run by test/nava_air.sh), on wall time.
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "lock_watch.h"

namespace multirobot_audio::testing {
namespace {

// ids 11, 30 and 212 (test/mutex_air.test)
const std::vector<std::string> kRobots = {"robot_0", "robot_1", "robot_2"};
// s each robot keeps the lock: a couple of lock announcements (every ~1.5 s).
constexpr double kHold = 3.0;

TEST(MutexAir, EachRobotGetsTheLockInTurnAndNeverTwoAtOnce) {
  ros::NodeHandle nh;
  LockWatch watch(nh, kRobots);
  std::vector<std::unique_ptr<LockUser>> users;
  std::vector<LockUser*> clients;
  for (const std::string& robot : kRobots) {
    users.push_back(std::make_unique<LockUser>(nh, robot));
    clients.push_back(users.back().get());
  }
  ASSERT_TRUE(watch.Ready(30.0)) << "the local_mutex nodes did not come up";
  for (LockUser* user : clients) ASSERT_TRUE(user->Ready(30.0)) << user->robot() << ": no acquire action or release service";
  // The links calibrate their carrier threshold on 1 s of silence first.
  ros::WallDuration(2.0).sleep();

  // Staggered by less than a request interval: all three ask before any request is on the air,
  // so all request at Lamport time 0 and the ids decide.
  for (LockUser* user : clients) {
    user->Acquire();
    ros::WallDuration(0.5).sleep();
  }
  std::string failure;
  EXPECT_TRUE(HoldAndReleaseEach(clients, kHold, 120.0, &failure)) << failure << Describe(watch.Grants());

  const std::vector<Grant>& grants = watch.Grants();
  EXPECT_TRUE(watch.Overlaps().empty()) << "two robots held the lock at once:" << Describe(grants);
  EXPECT_EQ(watch.MostHeldAtOnce(), 1);
  ASSERT_EQ(grants.size(), 3u) << Describe(grants);
  EXPECT_EQ(Robots(grants), Robots(InRequestOrder(grants))) << "grants out of request order:" << Describe(grants);
  for (const std::string& robot : kRobots) {
    EXPECT_EQ(watch.Latest(robot).duplicate_ids, 0u) << robot << " heard its own id from another robot";
  }
}

}  // namespace
}  // namespace multirobot_audio::testing
