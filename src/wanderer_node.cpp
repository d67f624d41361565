// wanderer: drives one robot around with obstacle avoidance (the placeholder team behaviour).
// Run it in the robot's namespace: it reads `scan` and writes `cmd_vel`. With ~robots (a list of
// robot namespaces) it drives all of them in one process instead, on world_sim's team topics
// (~scans_topic, ~commands_topic): the way to simulate big teams (docs/simulation.md).
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "params.h"
#include "wanderer_ros.h"
#include "wanderer_team_ros.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "wanderer");
  try {
    using multirobot_audio::ParamError;
    ros::NodeHandle nh, pnh("~");
    const double announce = multirobot_audio::NumberParam(pnh, "announce_period", 0.0, 0.0, 1e6);
    const std::vector<std::string> robots =
        multirobot_audio::StringListParam(pnh, "robots", "a list of robot namespaces, such as [robot_0, robot_1]");
    if (!robots.empty()) {
      if (pnh.hasParam("seed")) {
        throw ParamError(pnh.resolveName("seed") + ": with ~robots each robot's seed comes from its namespace; drop one of them");
      }
      multirobot_audio::WandererTeamRos::Options o;
      o.robots = robots;
      o.wander = multirobot_audio::ReadWanderOptions(pnh);
      o.announce_period = announce;
      o.scans_topic = multirobot_audio::StringParam(pnh, "scans_topic", o.scans_topic);
      o.commands_topic = multirobot_audio::StringParam(pnh, "commands_topic", o.commands_topic);
      std::unique_ptr<multirobot_audio::WandererTeamRos> team;
      try {
        team = std::make_unique<multirobot_audio::WandererTeamRos>(nh, o);
      } catch (const std::invalid_argument& e) {
        throw ParamError(pnh.resolveName("robots") + ": " + e.what());
      }
      ros::spin();
      return 0;
    }
    const int seed = multirobot_audio::IntParam(
        pnh, "seed", static_cast<int>(multirobot_audio::NamespaceSeed(nh.getNamespace())), 0, 2147483647);
    multirobot_audio::WandererRos node(nh, multirobot_audio::ReadWanderOptions(pnh),
                                       static_cast<std::uint32_t>(seed), announce);
    ros::spin();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wanderer: %s\n", e.what());
    return 1;
  }
  return 0;
}
