#include "wanderer_ros.h"

#include <algorithm>
#include <cstdio>
#include <functional>

#include <geometry_msgs/Twist.h>

#include "input_checks.h"
#include "params.h"

namespace multirobot_audio {

behaviours::WanderOptions ReadWanderOptions(const ros::NodeHandle& pnh) {
  behaviours::WanderOptions o;
  o.cruise_speed = NumberParam(pnh, "cruise_speed", o.cruise_speed);
  o.turn_rate = NumberParam(pnh, "turn_rate", o.turn_rate);
  o.avoid_range = NumberParam(pnh, "avoid_range", o.avoid_range);
  o.slow_range = NumberParam(pnh, "slow_range", std::max(o.slow_range, o.avoid_range + 0.1));
  CheckOptionParams(pnh, {"cruise_speed", "turn_rate", "avoid_range", "slow_range"},
                    [&] { behaviours::ValidateOptions(o); });
  return o;
}

std::uint32_t NamespaceSeed(const std::string& ns) {
  return static_cast<std::uint32_t>(std::hash<std::string>{}(ns) & 0x7fffffff);
}

multirobot_audio::AudioPacket AnnouncePacket(std::uint32_t seed, ros::Time stamp) {
  multirobot_audio::AudioPacket packet;
  packet.header.stamp = stamp;
  packet.data = {'W', static_cast<std::uint8_t>(seed >> 16), static_cast<std::uint8_t>(seed >> 8),
                 static_cast<std::uint8_t>(seed)};
  return packet;
}

geometry_msgs::Twist WanderStep(behaviours::Wanderer& wanderer, ros::Time& last_scan, const sensor_msgs::LaserScan& scan) {
  const double dt = last_scan.isZero() ? 0.1 : (scan.header.stamp - last_scan).toSec();
  last_scan = scan.header.stamp;
  const behaviours::VelocityCommand c = wanderer.Update(scan.ranges, std::max(dt, 0.0));
  geometry_msgs::Twist cmd;
  cmd.linear.x = c.v;
  cmd.angular.z = c.w;
  return cmd;
}

WandererRos::WandererRos(ros::NodeHandle nh, const behaviours::WanderOptions& options,
                         std::uint32_t seed, double announce_period)
    : nh_(nh), lockstep_(nh), wanderer_(options, seed), seed_(seed) {
  cmd_pub_ = lockstep_.Advertise<geometry_msgs::Twist>(nh_, "cmd_vel", 10);
  scan_sub_ = guard_.Subscribe<sensor_msgs::LaserScan>(
      lockstep_, nh_, "scan", 10, ScanProblem,
      [this](const sensor_msgs::LaserScan::ConstPtr& m) { OnScan(m); });
  if (announce_period > 0.0) {
    audio_pub_ = lockstep_.Advertise<multirobot_audio::AudioPacket>(nh_, "audio/tx", 10);
    announce_timer_ = lockstep_.CreateTimer(nh_, ros::Duration(announce_period), [this](const ros::TimerEvent&) {
      audio_pub_.publish(AnnouncePacket(seed_, ros::Time::now()));
    });
  }
}

WandererRos::~WandererRos() {
  // Printed directly: the node's logging is already shut down when it is destroyed.
  std::printf("wanderer summary: %s commands %lu; %s\n", nh_.getNamespace().c_str(),
              static_cast<unsigned long>(commands_), guard_.Summary().c_str());
  std::fflush(stdout);
}

void WandererRos::OnScan(const sensor_msgs::LaserScan::ConstPtr& scan) {
  cmd_pub_.publish(WanderStep(wanderer_, last_scan_, *scan));
  ++commands_;
}

}  // namespace multirobot_audio
