#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <multirobot_audio/RobotScans.h>
#include <ros/ros.h>

#include "input_guard.h"
#include "lockstep_participant.h"
#include "behaviours/wanderer.h"

namespace multirobot_audio {

// The wanderers of many robots in one process: the same controller as WandererRos for each robot
// in `robots` (namespaces), fed by world_sim's one message of every robot's scan (`scans_topic`)
// and answering with one message of every robot's command (`commands_topic`), so a simulated
// team of a hundred costs two messages a scan and one lockstep participant instead of a hundred
// processes. A robot's seed is NamespaceSeed of its resolved namespace, as a wanderer of its own
// would take, so the team drives exactly as separate wanderers do. Scans of robots not in
// `robots` are passed over (a world may have more robots than controllers).
class WandererTeamRos {
 public:
  struct Options {
    std::vector<std::string> robots;  // namespaces, relative to the node's
    behaviours::WanderOptions wander;
    double announce_period = 0.0;  // s between each robot's audio announcement; 0 = silent
    std::string scans_topic = "/world_sim/robot_scans";
    std::string commands_topic = "/world_sim/robot_commands";
  };

  // Throws std::invalid_argument naming the robot when a namespace is empty, invalid or given twice.
  WandererTeamRos(ros::NodeHandle nh, Options options);
  ~WandererTeamRos();

 private:
  struct Robot {
    std::string ns;  // resolved
    std::uint32_t seed = 0;
    behaviours::Wanderer wanderer;
    ros::Time last_scan;
    std::uint64_t commands = 0;
    CountedPublisher audio_pub;
  };
  void OnScans(const multirobot_audio::RobotScans::ConstPtr& msg);
  void Announce();

  ros::NodeHandle nh_;
  Options options_;
  LockstepParticipant lockstep_;  // before what it hands messages and timers to
  InputGuard guard_;              // before the subscription whose callbacks it checks
  std::vector<Robot> robots_;
  std::map<std::string, std::size_t> index_;  // robot name as world_sim gives it -> robots_
  ros::Subscriber scans_sub_;
  CountedPublisher commands_pub_;
  ros::Timer announce_timer_;
  std::uint64_t unknown_ = 0;  // scans of robots the team does not drive
};

}  // namespace multirobot_audio
