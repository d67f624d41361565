// sounds_good_explorer: one Sounds Good robot (thesis chapter 3), exploring with a local map
// and heard marker announcements to carry out the transport task. Run it in the robot's
// namespace beside the robot's audio link. See docs/nodes.md for its interface.
#include <cstdio>
#include <functional>
#include <string>

#include <ros/ros.h>

#include "sounds_good_explorer_ros.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "sounds_good_explorer");
  try {
    // Both handles live as long as the node: destroying the last handle shuts ROS down.
    ros::NodeHandle nh, pnh("~");
    // Robots differ by namespace, so their default seeds do too.
    const auto seed = static_cast<std::uint32_t>(std::hash<std::string>{}(nh.getNamespace()));
    multirobot_audio::SoundsGoodExplorerRos node(nh, pnh,
                                                 multirobot_audio::ReadSoundsGoodExplorerNodeOptions(pnh, seed));
    ros::spin();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sounds_good_explorer: %s\n", e.what());
    return 1;
  }
  return 0;
}
