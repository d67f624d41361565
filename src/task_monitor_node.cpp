// task_monitor: counts a Sounds Good team's jobs and reports how long the team took to reach
// its goal, then stops. See docs/nodes.md for its interface.
#include <cstdio>

#include <ros/ros.h>

#include "task_monitor_ros.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "task_monitor");
  try {
    ros::NodeHandle nh, pnh("~");
    multirobot_audio::TaskMonitorRos node(nh, multirobot_audio::ReadTaskMonitorOptions(pnh));
    ros::spin();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "task_monitor: %s\n", e.what());
    return 1;
  }
  return 0;
}
