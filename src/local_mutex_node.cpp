// local_mutex: one robot's audio-based local mutual exclusion (thesis chapter 7). Run it in the
// robot's namespace beside the robot's audio link. See docs/nodes.md for its interface.
#include <cstdio>
#include <stdexcept>

#include <ros/ros.h>

#include "local_mutex_ros.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "local_mutex");
  try {
    // Both handles live as long as the node: destroying the last handle shuts ROS down.
    ros::NodeHandle nh, pnh("~");
    multirobot_audio::LocalMutexRos node(nh, multirobot_audio::ReadLocalMutexNodeOptions(pnh));
    ros::spin();
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "%s\n", e.what());  // ValidateMutexOptions names the node itself
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "local_mutex: %s\n", e.what());
    return 1;
  }
  return 0;
}
