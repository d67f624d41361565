// wanderer: drives one robot around with obstacle avoidance (the placeholder team behaviour).
// Run it in the robot's namespace: it reads `scan` and writes `cmd_vel`.
#include <cstdio>
#include <functional>

#include <ros/ros.h>

#include "params.h"
#include "wanderer_ros.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "wanderer");
  try {
    ros::NodeHandle nh, pnh("~");
    // Robots differ by namespace, so their default seeds do too.
    const int seed = multirobot_audio::IntParam(
        pnh, "seed", static_cast<int>(std::hash<std::string>{}(nh.getNamespace()) & 0x7fffffff), 0,
        2147483647);
    const double announce = multirobot_audio::NumberParam(pnh, "announce_period", 0.0, 0.0, 1e6);
    multirobot_audio::WandererRos node(nh, multirobot_audio::ReadWanderOptions(pnh),
                                       static_cast<std::uint32_t>(seed), announce);
    ros::spin();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wanderer: %s\n", e.what());
    return 1;
  }
  return 0;
}
