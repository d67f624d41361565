// The main of the rostest gtest nodes that need nothing before their tests run: gtest, then a
// ROS node (its name comes from the .test file), held up while the tests run.
#include <gtest/gtest.h>
#include <ros/ros.h>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "rostest_gtest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
