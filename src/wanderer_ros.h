#pragma once

#include <cstdint>

#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include "world_sim/wanderer.h"

namespace multirobot_audio {

// Fills WanderOptions from ~cruise_speed, ~turn_rate, ~avoid_range, ~slow_range; throws
// ParamError on impossible values.
world_sim::WanderOptions ReadWanderOptions(const ros::NodeHandle& pnh);

// One robot's wandering controller: a cmd_vel for every scan. Runs in the robot's namespace,
// so it works the same on world_sim and on a robot whose driver publishes scan.
class WandererRos {
 public:
  WandererRos(ros::NodeHandle nh, const world_sim::WanderOptions& options, std::uint32_t seed);

 private:
  void OnScan(const sensor_msgs::LaserScan::ConstPtr& scan);

  ros::NodeHandle nh_;
  world_sim::Wanderer wanderer_;
  ros::Subscriber scan_sub_;
  ros::Publisher cmd_pub_;
  ros::Time last_scan_;
};

}  // namespace multirobot_audio
