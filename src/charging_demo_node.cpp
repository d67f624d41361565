// charging_demo: one charging robot (thesis section 7.2): works until its battery is low, finds
// a charger, waits for the robot's local mutex beside it, docks only while holding it, charges,
// backs away and lets go. Run it in the robot's namespace beside local_mutex. See docs/nodes.md and docs/real_robots.md.
#include <cstdio>
#include <functional>
#include <string>

#include <ros/ros.h>

#include "charging_demo_ros.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "charging_demo");
  try {
    // Both handles live as long as the node: destroying the last handle shuts ROS down.
    ros::NodeHandle nh, pnh("~");
    // Robots differ by namespace, so their default seeds do too.
    const auto seed = static_cast<std::uint32_t>(std::hash<std::string>{}(nh.getNamespace()));
    multirobot_audio::ChargingDemoRos node(nh, pnh, multirobot_audio::ReadChargingDemoNodeOptions(pnh, seed));
    ros::spin();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "charging_demo: %s\n", e.what());
    return 1;
  }
  return 0;
}
