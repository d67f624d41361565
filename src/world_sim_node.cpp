// world_sim: the team's simulated world and clock. See docs/nodes.md for topics and parameters.
#include <cstdio>

#include <ros/ros.h>

#include "params.h"
#include "world_sim_ros.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "world_sim");
  try {
    ros::NodeHandle pnh("~");
    multirobot_audio::WorldSimRos sim(ros::NodeHandle(), pnh, multirobot_audio::ReadWorldSimOptions(pnh));
    std::printf("%s\n", sim.Run().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "world_sim: %s\n", e.what());
    return 1;
  }
  return 0;
}
