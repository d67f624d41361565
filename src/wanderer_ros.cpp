#include "wanderer_ros.h"

#include <algorithm>
#include <cstdio>

#include <geometry_msgs/Twist.h>
#include <multirobot_audio/AudioPacket.h>

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
      multirobot_audio::AudioPacket packet;
      packet.header.stamp = ros::Time::now();
      packet.data = {'W', static_cast<std::uint8_t>(seed_ >> 16), static_cast<std::uint8_t>(seed_ >> 8),
                     static_cast<std::uint8_t>(seed_)};
      audio_pub_.publish(packet);
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
  // The behaviour wants ranger 0 ahead and an even ring, which is what world_sim publishes.
  const double dt = last_scan_.isZero() ? 0.1 : (scan->header.stamp - last_scan_).toSec();
  last_scan_ = scan->header.stamp;
  const behaviours::VelocityCommand c = wanderer_.Update(scan->ranges, std::max(dt, 0.0));
  geometry_msgs::Twist cmd;
  cmd.linear.x = c.v;
  cmd.angular.z = c.w;
  cmd_pub_.publish(cmd);
  ++commands_;
}

}  // namespace multirobot_audio
