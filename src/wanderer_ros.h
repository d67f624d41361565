#pragma once

#include <cstdint>

#include <geometry_msgs/Twist.h>
#include <multirobot_audio/AudioPacket.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include "input_guard.h"
#include "lockstep_participant.h"
#include "behaviours/wanderer.h"

namespace multirobot_audio {

// Fills WanderOptions from ~cruise_speed, ~turn_rate, ~avoid_range, ~slow_range; throws
// ParamError naming the parameter on values behaviours::ValidateOptions refuses.
behaviours::WanderOptions ReadWanderOptions(const ros::NodeHandle& pnh);

// A robot's default seed: robots differ by namespace, so their seeds do too.
std::uint32_t NamespaceSeed(const std::string& ns);

// One step of a robot's wanderer on its scan: the command, with the time since `last_scan` (0.1 s
// at the first), which it then sets to the scan's stamp. The behaviour wants ranger 0 ahead and an
// even ring, which is what world_sim publishes.
geometry_msgs::Twist WanderStep(behaviours::Wanderer& wanderer, ros::Time& last_scan, const sensor_msgs::LaserScan& scan);

// A wanderer's announcement: 'W' and the three low bytes of `seed`.
multirobot_audio::AudioPacket AnnouncePacket(std::uint32_t seed, ros::Time stamp);

// One robot's wandering controller: a cmd_vel for every scan. Runs in the robot's namespace,
// so it works the same on world_sim and on a robot whose driver publishes scan.
class WandererRos {
 public:
  // With `announce_period` > 0 s it also sends a packet on audio/tx that often (simulated
  // time): 'W' and the three low bytes of `seed`, so listeners can tell robots apart.
  WandererRos(ros::NodeHandle nh, const behaviours::WanderOptions& options, std::uint32_t seed,
              double announce_period = 0.0);
  ~WandererRos();

 private:
  void OnScan(const sensor_msgs::LaserScan::ConstPtr& scan);

  ros::NodeHandle nh_;
  LockstepParticipant lockstep_;  // before what it hands messages and timers to
  InputGuard guard_;              // before the subscriptions whose callbacks it checks
  behaviours::Wanderer wanderer_;
  ros::Subscriber scan_sub_;
  CountedPublisher cmd_pub_, audio_pub_;
  ros::Timer announce_timer_;
  std::uint32_t seed_;
  ros::Time last_scan_;
  std::uint64_t commands_ = 0;
};

}  // namespace multirobot_audio
