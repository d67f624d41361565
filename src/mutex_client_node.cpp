// mutex_client: acquires the robot's local mutex, holds it, releases it, pauses, and again.
// Run it in the robot's namespace beside local_mutex.
#include <cstdio>

#include <ros/ros.h>

#include "mutex_client_ros.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mutex_client");
  try {
    // Both handles live as long as the node: destroying the last handle shuts ROS down.
    ros::NodeHandle nh, pnh("~");
    multirobot_audio::MutexClient client(nh, multirobot_audio::ReadMutexClientOptions(pnh));
    // Run() blocks; the global queue (the input guard's timers) is served beside it.
    ros::AsyncSpinner spinner(1);
    spinner.start();
    client.Run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mutex_client: %s\n", e.what());
    return 1;
  }
  return 0;
}
