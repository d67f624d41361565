#include "wanderer_team_ros.h"

#include <cstdio>
#include <set>
#include <stdexcept>

#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/RobotCommands.h>

#include "input_checks.h"
#include "wanderer_ros.h"

namespace multirobot_audio {

WandererTeamRos::WandererTeamRos(ros::NodeHandle nh, Options options)
    : nh_(nh), options_(std::move(options)), lockstep_(nh) {
  std::set<std::string> seen;
  robots_.reserve(options_.robots.size());
  for (const std::string& name : options_.robots) {
    std::string ns;
    try {
      ns = name.empty() ? std::string() : ros::NodeHandle(nh_, name).getNamespace();
    } catch (const ros::InvalidNameException& e) {
      throw std::invalid_argument("robot '" + name + "': " + e.what());
    }
    if (ns.empty() || !seen.insert(ns).second) {
      throw std::invalid_argument("robot '" + name + "': expected a distinct, non-empty robot namespace");
    }
    const std::uint32_t seed = NamespaceSeed(ns);
    robots_.push_back(Robot{ns, seed, behaviours::Wanderer(options_.wander, seed), {}, 0, {}});
    // world_sim names a robot by its namespace below the root.
    index_[ns.substr(ns.rfind('/') + 1)] = robots_.size() - 1;
    if (options_.announce_period > 0.0) {
      ros::NodeHandle rnh(ns);
      robots_.back().audio_pub = lockstep_.Advertise<multirobot_audio::AudioPacket>(rnh, "audio/tx", 10);
    }
  }
  commands_pub_ = lockstep_.Advertise<multirobot_audio::RobotCommands>(nh_, options_.commands_topic, 10);
  scans_sub_ = guard_.Subscribe<multirobot_audio::RobotScans>(
      lockstep_, nh_, options_.scans_topic, 10, RobotScansProblem,
      [this](const multirobot_audio::RobotScans::ConstPtr& m) { OnScans(m); });
  // One timer for the team: the wanderers' own timers would all fall due at the same times.
  if (options_.announce_period > 0.0) {
    announce_timer_ = lockstep_.CreateTimer(nh_, ros::Duration(options_.announce_period),
                                            [this](const ros::TimerEvent&) { Announce(); });
  }
}

WandererTeamRos::~WandererTeamRos() {
  // Printed directly: the node's logging is already shut down when it is destroyed.
  for (const Robot& r : robots_) {
    std::printf("wanderer summary: %s commands %lu\n", r.ns.c_str(), static_cast<unsigned long>(r.commands));
  }
  std::printf("wanderer summary: team of %zu, scans of other robots %lu; %s\n", robots_.size(),
              static_cast<unsigned long>(unknown_), guard_.Summary().c_str());
  std::fflush(stdout);
}

void WandererTeamRos::Announce() {
  const ros::Time now = ros::Time::now();
  for (Robot& r : robots_) r.audio_pub.publish(AnnouncePacket(r.seed, now));
}

void WandererTeamRos::OnScans(const multirobot_audio::RobotScans::ConstPtr& msg) {
  multirobot_audio::RobotCommands out;
  out.names.reserve(msg->names.size());
  out.commands.reserve(msg->names.size());
  for (std::size_t k = 0; k < msg->names.size(); ++k) {
    const auto it = index_.find(msg->names[k]);
    if (it == index_.end()) {
      ++unknown_;
      continue;
    }
    Robot& r = robots_[it->second];
    out.names.push_back(msg->names[k]);
    out.commands.push_back(WanderStep(r.wanderer, r.last_scan, msg->scans[k]));
    ++r.commands;
  }
  if (!out.names.empty()) commands_pub_.publish(out);
}

}  // namespace multirobot_audio
