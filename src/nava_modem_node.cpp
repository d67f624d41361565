// nava_modem: a robot's audio link on its sound card. See docs/nodes.md for topics and parameters.
#include <cstdio>

#include <ros/ros.h>

#include "nava_modem_ros.h"
#include "params.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "nava_modem");
  try {
    ros::NodeHandle pnh("~");
    multirobot_audio::NavaModemRos node(ros::NodeHandle(), pnh, multirobot_audio::ReadNavaModemOptions(ros::NodeHandle(), pnh));
    ros::spin();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nava_modem: %s\n", e.what());
    return 1;
  }
  return 0;
}
