// rostest of the lockstep (test/lockstep.test): this node is a participant that holds one step
// up for 1.5 s and later stops answering for 4.5 s; world_sim's timeout is 3 s.
#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/LaserScan.h>

#include "lockstep_participant.h"
#include "wait_for.h"

namespace {

using multirobot_audio::testing::WaitFor;

TEST(Lockstep, TheWorldWaitsForASlowParticipantAndDropsOneThatStopsAnswering) {
  ros::NodeHandle nh;
  // Watched on a thread of its own, since the participant's callbacks hold the main thread up.
  ros::CallbackQueue watch_queue;
  ros::NodeHandle wnh;
  wnh.setCallbackQueue(&watch_queue);
  std::atomic<double> clock{0.0};
  std::mutex mutex;
  std::vector<std::string> warnings;
  auto clock_sub = wnh.subscribe<rosgraph_msgs::Clock>(
      "/clock", 1000, [&](const rosgraph_msgs::Clock::ConstPtr& c) { clock = c->clock.toSec(); });
  auto log_sub = wnh.subscribe<rosgraph_msgs::Log>("/rosout", 1000, [&](const rosgraph_msgs::Log::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    if (m->level >= rosgraph_msgs::Log::WARN) warnings.push_back(m->name + ": " + m->msg);
  });
  ros::AsyncSpinner watcher(1, &watch_queue);
  watcher.start();

  multirobot_audio::LockstepParticipant lockstep(nh);
  ASSERT_TRUE(lockstep.enabled());
  int ticks = 0, scans = 0;
  double held_at = -1.0, clock_in_hold = -1.0, stopped_at = -1.0, clock_after_stop = -1.0;
  auto scan_sub = lockstep.Subscribe<sensor_msgs::LaserScan>(
      nh, "/robot_0/scan", 10, [&](const sensor_msgs::LaserScan::ConstPtr&) { ++scans; });
  ros::Timer timer = lockstep.CreateTimer(nh, ros::Duration(0.1), [&](const ros::TimerEvent& e) {
    ++ticks;
    EXPECT_DOUBLE_EQ(ros::Time::now().toSec(), e.current_real.toSec());
    if (ticks == 20) {
      held_at = e.current_real.toSec();
      ros::WallDuration(1.5).sleep();
      clock_in_hold = clock;
    } else if (ticks == 30) {
      stopped_at = e.current_real.toSec();
      ros::WallDuration(4.5).sleep();
      clock_after_stop = clock;
    }
  });
  ASSERT_TRUE(WaitFor([&] { return clock_after_stop >= 0.0; }, 90.0)) << "ticks " << ticks;
  // While the step was held up, simulated time stood still at the step's time.
  EXPECT_DOUBLE_EQ(clock_in_hold, held_at);
  // After the timeout the world went on without the silent participant.
  EXPECT_GT(clock_after_stop, stopped_at + 1.0);
  EXPECT_GT(scans, 10);  // the scans of robot_0 came through the inbox
  ASSERT_TRUE(WaitFor(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& w : warnings) {
          if (w.find("/lockstep_rostest has not answered") != std::string::npos &&
              w.find("dropped from the lockstep") != std::string::npos) {
            return true;
          }
        }
        return false;
      },
      10.0));
  // Dropped for good: no more orders, so the timer stays quiet while the world goes on.
  const int ticks_after = ticks;
  const double clock_then = clock;
  WaitFor([&] { return clock > clock_then + 5.0; }, 20.0);
  EXPECT_EQ(ticks, ticks_after);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "lockstep_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
