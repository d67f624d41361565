#include "sounds_good_explorer_ros.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <geometry_msgs/Twist.h>
#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/Job.h>
#include <visualization_msgs/Marker.h>

#include "conversions.h"
#include "input_checks.h"
#include "navigation_conversions.h"
#include "navigation_params.h"
#include "params.h"

namespace multirobot_audio {
namespace {

namespace sg = sounds_good_explorer;

constexpr int kMaxInt = std::numeric_limits<int>::max();

unsigned long Count(std::uint64_t n) { return static_cast<unsigned long>(n); }

}  // namespace

SoundsGoodExplorerNodeOptions ReadSoundsGoodExplorerNodeOptions(const ros::NodeHandle& pnh,
                                                                std::uint32_t default_seed) {
  SoundsGoodExplorerNodeOptions o;
  sg::ExplorerOptions& e = o.explorer;
  const std::string mode = StringParam(pnh, "mode", sg::ListenModeName(e.mode));
  const std::optional<sg::ListenMode> parsed = sg::ParseListenMode(mode);
  if (!parsed) {
    throw ParamError(pnh.resolveName("mode") + ": expected omni, bidirectional or none, got '" + mode + "'");
  }
  e.mode = *parsed;
  // Wide bounds here catch the wrong type and nonsense; ValidateOptions below says what the
  // explorer needs of each value and of the values together.
  e.task.source = static_cast<std::uint32_t>(IntParam(pnh, "source", static_cast<int>(e.task.source), 0, kMaxInt));
  e.task.sink = static_cast<std::uint32_t>(IntParam(pnh, "sink", static_cast<int>(e.task.sink), 0, kMaxInt));
  e.task.work_time = NumberParam(pnh, "work_time", e.task.work_time, 0.0, 1e6);
  e.task.arrive_radius = NumberParam(pnh, "arrive_radius", e.task.arrive_radius, 0.0, 1e3);
  e.task.marker_memory = NumberParam(pnh, "marker_memory", e.task.marker_memory, 0.0, 1e6);
  e.task.announce_window = NumberParam(pnh, "announce_window", e.task.announce_window, 0.0, 1e6);
  e.task.announce_period = NumberParam(pnh, "announce_period", e.task.announce_period, 0.0, 1e6);
  ReadNavigationParams(pnh, e.map, e.clear_sectors, e.planner, e.motion);
  e.frontier.audio_weight = NumberParam(pnh, "audio_weight", e.frontier.audio_weight, 0.0, 1e6);
  e.frontier.noise_std = NumberParam(pnh, "noise_std", e.frontier.noise_std, 0.0, 1e6);
  e.frontier.min_distance = NumberParam(pnh, "min_frontier_distance", e.frontier.min_distance, 0.0, 1e6);
  e.audio.level_floor_db = NumberParam(pnh, "level_floor_db", e.audio.level_floor_db, -1e3, 1e3);
  e.audio.level_full_db = NumberParam(pnh, "level_full_db", e.audio.level_full_db, -1e3, 1e3);
  e.seed = static_cast<std::uint32_t>(IntParam(pnh, "seed", static_cast<int>(default_seed & 0x7fffffff), 0, kMaxInt));
  o.control_rate = NumberParam(pnh, "control_rate", o.control_rate, 0.1, 1000.0);
  o.map_rate = NumberParam(pnh, "map_rate", o.map_rate, 0.0, 1000.0);
  try {
    sg::ValidateOptions(e);
  } catch (const std::invalid_argument& error) {
    throw ParamError(pnh.getNamespace() + ": the parameters give impossible explorer options: " + error.what());
  }
  return o;
}

SoundsGoodExplorerRos::SoundsGoodExplorerRos(ros::NodeHandle nh, ros::NodeHandle pnh,
                                             const SoundsGoodExplorerNodeOptions& options)
    : nh_(nh), pnh_(pnh), lockstep_(nh), options_(options), explorer_(options.explorer) {
  cmd_pub_ = lockstep_.Advertise<geometry_msgs::Twist>(nh_, "cmd_vel", 10);
  tx_pub_ = lockstep_.Advertise<multirobot_audio::AudioPacket>(nh_, "audio/tx", 10);
  jobs_pub_ = lockstep_.Advertise<multirobot_audio::Job>(nh_, "jobs", 10);
  map_pub_ = pnh_.advertise<nav_msgs::OccupancyGrid>("local_map", 1);
  plan_pub_ = pnh_.advertise<nav_msgs::Path>("plan", 1);
  frontier_pub_ = pnh_.advertise<visualization_msgs::Marker>("frontier", 1);
  odom_sub_ = guard_.Subscribe<nav_msgs::Odometry>(
      lockstep_, nh_, "odom", 10, OdometryProblem,
      [this](const nav_msgs::Odometry::ConstPtr& m) { OnOdometry(m); });
  scan_sub_ = guard_.Subscribe<sensor_msgs::LaserScan>(
      lockstep_, nh_, "scan", 10, ScanProblem,
      [this](const sensor_msgs::LaserScan::ConstPtr& m) { OnScan(m); });
  fiducials_sub_ = guard_.Subscribe<multirobot_audio::FiducialArray>(
      lockstep_, nh_, "fiducials", 10, FiducialsProblem,
      [this](const multirobot_audio::FiducialArray::ConstPtr& m) { OnFiducials(m); });
  // Announcements come in bursts from several robots; none may be lost to a short queue.
  rx_sub_ = guard_.Subscribe<multirobot_audio::AudioReception>(
      lockstep_, nh_, "audio/rx", 50, ReceptionProblem,
      [this](const multirobot_audio::AudioReception::ConstPtr& m) { OnRx(m); });
  control_timer_ = lockstep_.CreateTimer(nh_, ros::Duration(1.0 / options_.control_rate), &SoundsGoodExplorerRos::OnControl, this);
  if (options_.map_rate > 0.0) {
    map_timer_ = lockstep_.CreateTimer(nh_, ros::Duration(1.0 / options_.map_rate), &SoundsGoodExplorerRos::PublishLocalMap, this);
  }
  const sg::TaskOptions& t = options_.explorer.task;
  ROS_INFO("sounds_good_explorer %s: %s audio, source %u, sink %u, %.0f s of work at each, control at %.1f Hz",
           nh_.getNamespace().c_str(), sg::ListenModeName(options_.explorer.mode), t.source, t.sink, t.work_time,
           options_.control_rate);
}

SoundsGoodExplorerRos::~SoundsGoodExplorerRos() {
  // Printed directly: the node's logging is already shut down when it is destroyed.
  std::printf("sounds_good_explorer summary: %s jobs %lu, packets sent %lu, heard %lu (foreign %lu), stuck %lu, "
              "plans %lu, late updates %lu of %lu; %s\n",
              nh_.getNamespace().c_str(), Count(jobs_), Count(sent_), Count(heard_),
              Count(explorer_.foreign_packets()), Count(explorer_.stuck_count()), Count(explorer_.plans()),
              Count(late_), Count(updates_), guard_.Summary().c_str());
  std::fflush(stdout);
}

void SoundsGoodExplorerRos::OnOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  odom_frame_ = msg->header.frame_id;
  base_frame_ = msg->child_frame_id;
  explorer_.OnOdometry(FromPose(msg->pose.pose), msg->header.stamp.toSec());
}

void SoundsGoodExplorerRos::OnScan(const sensor_msgs::LaserScan::ConstPtr& msg) {
  // Ranges are measured from the robot's centre (world_sim's IR ring, as the explorer wants);
  // range_max is how far the rangers reach from there.
  explorer_.OnRanges(ToRangeReadings(*msg), msg->range_max, msg->header.stamp.toSec());
}

void SoundsGoodExplorerRos::OnFiducials(const multirobot_audio::FiducialArray::ConstPtr& msg) {
  std::vector<sg::MarkerSighting> sightings;
  sightings.reserve(msg->fiducials.size());
  for (const multirobot_audio::Fiducial& f : msg->fiducials) sightings.push_back({f.id, f.range, f.bearing});
  explorer_.OnSightings(sightings, msg->header.stamp.toSec());
}

void SoundsGoodExplorerRos::OnRx(const multirobot_audio::AudioReception::ConstPtr& msg) {
  // Noise carries no announcement; the explorer has no use for it.
  if (msg->kind != multirobot_audio::AudioReception::PACKET) return;
  ++heard_;
  explorer_.OnHeard(msg->data, msg->level_db, msg->direction, msg->header.stamp.toSec());
}

void SoundsGoodExplorerRos::OnControl(const ros::TimerEvent& event) {
  const ros::Time now = ros::Time::now();
  // An update more than half a period behind its schedule: the node does not keep up with the
  // simulated clock (too high a real-time factor for the machine).
  if ((now - event.current_expected).toSec() > 0.5 / options_.control_rate) ++late_;
  ++updates_;
  const sg::ExplorerOutput out = explorer_.Update(now.toSec());
  geometry_msgs::Twist cmd;
  cmd.linear.x = out.v;
  cmd.angular.z = out.w;
  cmd_pub_.publish(cmd);
  for (const auto& packet : out.packets) {
    multirobot_audio::AudioPacket msg;
    msg.header.stamp = now;
    msg.header.frame_id = base_frame_;
    msg.data.assign(packet.begin(), packet.end());
    tx_pub_.publish(msg);
    ++sent_;
  }
  if (out.job) {
    jobs_ = static_cast<std::uint64_t>(out.job->count);
    multirobot_audio::Job msg;
    msg.header.stamp = ros::Time(out.job->time);
    msg.header.frame_id = base_frame_;
    msg.count = static_cast<std::uint32_t>(out.job->count);
    msg.marker = out.job->marker;
    jobs_pub_.publish(msg);
    ROS_INFO("sounds_good_explorer %s: job %d done at marker %u (%.1f s)", nh_.getNamespace().c_str(),
             out.job->count, out.job->marker, out.job->time);
  }
  // Only for rviz: skip building them when nobody looks (at high speed this runs often).
  if (odom_frame_.empty()) return;
  if (plan_pub_.getNumSubscribers() > 0) plan_pub_.publish(ToPath(explorer_.plan(), odom_frame_, now));
  if (frontier_pub_.getNumSubscribers() > 0) PublishFrontier(now);
}

void SoundsGoodExplorerRos::PublishLocalMap(const ros::TimerEvent&) {
  if (odom_frame_.empty() || map_pub_.getNumSubscribers() == 0) return;
  map_pub_.publish(ToOccupancyGrid(explorer_.local_map(), odom_frame_, ros::Time::now()));
}

void SoundsGoodExplorerRos::PublishFrontier(const ros::Time& now) {
  const std::optional<Eigen::Vector2d> goal = explorer_.goal();
  if (!goal && !frontier_shown_) return;
  visualization_msgs::Marker m;
  m.header.frame_id = odom_frame_;
  m.header.stamp = now;
  m.ns = "frontier";
  m.id = 0;
  if (!goal) {
    m.action = visualization_msgs::Marker::DELETE;
    frontier_pub_.publish(m);
    frontier_shown_ = false;
    return;
  }
  m.type = visualization_msgs::Marker::SPHERE;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.position.x = goal->x();
  m.pose.position.y = goal->y();
  m.pose.position.z = 0.1;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 0.3;
  // Cyan while exploring a frontier, orange once the sought marker itself is the goal.
  const bool marker = explorer_.goal_is_marker();
  m.color.r = marker ? 1.0f : 0.0f;
  m.color.g = marker ? 0.55f : 0.9f;
  m.color.b = marker ? 0.0f : 0.9f;
  m.color.a = 0.9f;
  frontier_pub_.publish(m);
  frontier_shown_ = true;
}

}  // namespace multirobot_audio
