// rostest for launch/record.launch (test/record.test): the bag it writes holds every topic a
// replay needs, as `rosbag info` lists them.
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <ros/ros.h>

namespace {

std::string RunCommand(const std::string& command, int* status) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> buf;
  while (fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  *status = pclose(pipe);
  return out;
}

TEST(RecordLaunch, WritesABagWithEveryExpectedTopic) {
  ros::NodeHandle pnh("~");
  std::string bag;
  ASSERT_TRUE(pnh.getParam("bag", bag));
  // rosbag writes BAG.active and renames it to BAG when its duration is up.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(90.0);
  while (!std::filesystem::exists(bag) && ros::WallTime::now() < end) ros::WallDuration(0.2).sleep();
  ASSERT_TRUE(std::filesystem::exists(bag)) << "no bag at " << bag;
  ros::WallDuration(0.5).sleep();

  int status = -1;
  const std::string info = RunCommand("rosbag info " + bag + " 2>&1", &status);
  ASSERT_EQ(status, 0) << info;
  for (const char* topic : {"/clock", "/tf", "/map", "/robot_0/scan", "/robot_0/odom",
                            "/robot_0/ground_truth", "/robot_0/fiducials", "/robot_0/battery",
                            "/robot_1/scan", "/robot_1/odom"}) {
    EXPECT_NE(info.find(std::string(topic) + " "), std::string::npos) << topic << " missing from\n" << info;
  }
  EXPECT_EQ(info.find("/rosout "), std::string::npos) << info;
  std::filesystem::remove(bag);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "record_rostest");
  ros::NodeHandle nh;
  // A bag left by an earlier run would pass the test on its own.
  std::string bag;
  if (ros::NodeHandle("~").getParam("bag", bag)) std::filesystem::remove(bag);
  return RUN_ALL_TESTS();
}
