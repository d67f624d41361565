// rostest for the world_sim node in the two-robot test room (test/world_sim.test).
#include <cmath>

#include <geometry_msgs/Twist.h>
#include <gtest/gtest.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "wait_for.h"

namespace {

using multirobot_audio::testing::WaitFor;

TEST(WorldSimNode, PublishesALatchedMap) {
  ros::NodeHandle nh;
  nav_msgs::OccupancyGrid::ConstPtr map;
  auto sub = nh.subscribe<nav_msgs::OccupancyGrid>("/map", 1, [&](const nav_msgs::OccupancyGrid::ConstPtr& m) { map = m; });
  ASSERT_TRUE(WaitFor([&] { return map != nullptr; }, 30.0));
  EXPECT_EQ(map->info.width, 120u);
  EXPECT_EQ(map->info.height, 80u);
  EXPECT_EQ(map->header.frame_id, "map");
}

TEST(WorldSimNode, ClockAdvancesAtAboutSpeedTimesWallTime) {
  ros::NodeHandle nh, pnh("~");
  double speed = 1.0;
  pnh.getParam("speed", speed);
  double sim = 0.0;
  auto sub = nh.subscribe<rosgraph_msgs::Clock>("/clock", 100, [&](const rosgraph_msgs::Clock::ConstPtr& c) { sim = c->clock.toSec(); });
  ASSERT_TRUE(WaitFor([&] { return sim > 0.0; }, 30.0));
  const double sim0 = sim;
  const ros::WallTime wall0 = ros::WallTime::now();
  WaitFor([] { return false; }, 3.0);
  const double ratio = (sim - sim0) / (ros::WallTime::now() - wall0).toSec();
  // Pacing never runs ahead of speed; a loaded machine may fall a little behind.
  EXPECT_LT(ratio, speed * 1.1);
  EXPECT_GT(ratio, speed * 0.6);
}

TEST(WorldSimNode, TfResolvesMapToBaseLinkAsGroundTruth) {
  ros::NodeHandle nh;
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  nav_msgs::Odometry::ConstPtr truth;
  auto sub = nh.subscribe<nav_msgs::Odometry>("/robot_1/ground_truth", 10, [&](const nav_msgs::Odometry::ConstPtr& m) { truth = m; });
  ASSERT_TRUE(WaitFor([&] { return truth != nullptr && buffer.canTransform("map", "robot_1/base_link", ros::Time(0)); }, 30.0));
  const auto t = buffer.lookupTransform("map", "robot_1/base_link", ros::Time(0));
  // robot_1 stands still at its start pose.
  EXPECT_NEAR(t.transform.translation.x, 4.5, 1e-6);
  EXPECT_NEAR(t.transform.translation.y, 1.0, 1e-6);
  EXPECT_NEAR(truth->pose.pose.position.x, 4.5, 1e-6);
  EXPECT_EQ(t.header.frame_id, "map");
}

TEST(WorldSimNode, RobotDrivenAtAWallStopsBeforeItAndScansIt) {
  ros::NodeHandle nh;
  auto cmd = nh.advertise<geometry_msgs::Twist>("/robot_0/cmd_vel", 10);
  sensor_msgs::LaserScan::ConstPtr scan;
  nav_msgs::Odometry::ConstPtr truth;
  auto scan_sub = nh.subscribe<sensor_msgs::LaserScan>("/robot_0/scan", 10, [&](const sensor_msgs::LaserScan::ConstPtr& m) { scan = m; });
  auto truth_sub = nh.subscribe<nav_msgs::Odometry>("/robot_0/ground_truth", 10, [&](const nav_msgs::Odometry::ConstPtr& m) { truth = m; });
  ASSERT_TRUE(WaitFor([&] { return scan && truth; }, 30.0));
  EXPECT_EQ(scan->ranges.size(), 8u);
  EXPECT_EQ(scan->header.frame_id, "robot_0/base_link");

  // Drive at full speed towards the wall face at x = 3.0 until the robot no longer moves.
  geometry_msgs::Twist ahead;
  ahead.linear.x = 0.3;
  double last_x = -1.0;
  int still = 0;
  const bool stopped = WaitFor([&] {
    cmd.publish(ahead);
    ros::WallDuration(0.02).sleep();
    ros::spinOnce();
    const double x = truth->pose.pose.position.x;
    still = std::abs(x - last_x) < 1e-9 ? still + 1 : 0;
    last_x = x;
    return still > 20 && x > 2.0;
  }, 60.0);
  ASSERT_TRUE(stopped) << "robot_0 did not stop; last x " << last_x;
  const double x = truth->pose.pose.position.x;
  EXPECT_LE(x, 3.0 - 0.075 + 1e-9);
  EXPECT_GT(x, 3.0 - 0.075 - 0.01);
  // The front ranger reads the distance from the centre to the wall face.
  ASSERT_TRUE(WaitFor([&] { return scan->header.stamp > truth->header.stamp; }, 10.0));
  EXPECT_NEAR(scan->ranges[0], 3.0 - x, 1e-3);
}

}  // namespace
