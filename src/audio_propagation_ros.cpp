#include "audio_propagation_ros.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/CarrierSense.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/topic.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.h"
#include "rviz_markers.h"
#include "input_checks.h"
#include "audio_propagation/delivery_map.h"
#include "params.h"
#include "nava_modem/modem_profile.h"

namespace multirobot_audio {
namespace {

constexpr double kUnknown = -1e6;  // where a robot with no pose yet is put: off every map

}  // namespace

AudioPropagationOptions ReadAudioPropagationOptions(const ros::NodeHandle& pnh) {
  AudioPropagationOptions o;
  audio_propagation::SimulatedChannelOptions& c = o.channel;
  c.world_file = StringParam(pnh, "world", c.world_file);
  c.map_file = StringParam(pnh, "map", c.map_file);
  c.robots = StringListParam(pnh, "robots", "a list of robot names");
  c.microphones = StringListParam(pnh, "microphones", "a list of omni, bidirectional or none");
  c.bit_rate = OptionalNumberParam(pnh, "bit_rate");
  c.decode_table = StringParam(pnh, "decode_table", c.decode_table);
  c.delivery_map_robot = StringParam(pnh, "delivery_map_robot", c.delivery_map_robot);
  c.source_level_db = NumberParam(pnh, "source_level_db", c.source_level_db);
  c.threshold_db = OptionalNumberParam(pnh, "threshold_db");
  c.max_range = NumberParam(pnh, "max_range", c.max_range);
  c.speed_of_sound = NumberParam(pnh, "speed_of_sound", c.speed_of_sound);
  c.capture_margin_db = NumberParam(pnh, "capture_margin_db", c.capture_margin_db);
  c.direction_noise = NumberParam(pnh, "direction_noise", c.direction_noise);
  const std::string directions = StringParam(pnh, "directions", "exact");
  if (directions != "exact" && directions != "measured") {
    throw ParamError(pnh.resolveName("directions") + ": expected exact or measured, got '" + directions + "'");
  }
  c.measured_directions = directions == "measured";
  c.direction_table = StringParam(pnh, "direction_table", c.direction_table);
  c.seed = IntParam(pnh, "seed", c.seed);
  c.rate = IntParam(pnh, "rate", c.rate);
  c.cache_size = IntParam(pnh, "cache_size", c.cache_size);
  c.link_fate = BoolParam(pnh, "link_fate", c.link_fate);
  c.fate_distance = NumberParam(pnh, "fate_distance", c.fate_distance);
  try {
    c.profile = audio_propagation::ParseProfileOption(StringParam(pnh, "profile", nava_modem::ProfileName(c.profile)));
    c.channel_model = audio_propagation::ParseChannelModel(
        StringParam(pnh, "channel_model", audio_propagation::ChannelModelName(c.channel_model)));
    c.rule = audio_propagation::ParseRuleOption(StringParam(pnh, "rule", audio_propagation::DiffractionRuleName(c.rule)));
    audio_propagation::CheckSimulatedChannelOptions(c);
  } catch (const audio_propagation::ChannelOptionError& e) {
    throw OptionParamError(pnh, e.field(), e.problem());
  }

  o.frame_id = StringParam(pnh, "frame_id", o.frame_id);
  o.map_timeout = NumberParam(pnh, "map_timeout", o.map_timeout, 0.0, 1e6);
  o.update_rate = NumberParam(pnh, "update_rate", o.update_rate, 1.0, 10000.0);
  const std::string update = StringParam(pnh, "update", "events");
  if (update != "events" && update != "every_step") {
    throw ParamError(pnh.resolveName("update") + ": expected events or every_step, got '" + update + "'");
  }
  o.every_step = update == "every_step";
  o.carrier_refresh = NumberParam(pnh, "carrier_refresh", o.carrier_refresh, 0.01, 3600.0);
  o.path_display_time = NumberParam(pnh, "path_display_time", o.path_display_time, 0.0, 3600.0);
  if (pnh.hasParam("packet_bytes")) {
    // It once let packets of any length through while they still sounded as long as 4 bytes.
    throw ParamError(pnh.resolveName("packet_bytes") +
                     ": no longer read: the profile sets the lengths a frame may have (nava 4 bytes; room 1 to 255, "
                     "each lasting its own airtime at ~rate)");
  }
  o.robot_poses = StringParam(pnh, "robot_poses", o.robot_poses);
  o.delivery_map_period = NumberParam(pnh, "delivery_map_period", o.delivery_map_period, 0.1, 1e6);
  o.delivery_map_resolution = NumberParam(pnh, "delivery_map_resolution", o.delivery_map_resolution, 0.01, 100.0);
  o.ranging = ReadSimRangingOptions(pnh, c.speed_of_sound);
  return o;
}

AudioPropagationRos::AudioPropagationRos(ros::NodeHandle nh, ros::NodeHandle pnh,
                                         const AudioPropagationOptions& options)
    : nh_(nh), pnh_(pnh), lockstep_(nh), updater_(nh, pnh), guard_(updater_), options_(options),
      tf_listener_(lockstep_.enabled() ? nullptr : std::make_unique<tf2_ros::TransformListener>(tf_buffer_)) {
  std::optional<grid::OccupancyMap> map;
  if (audio_propagation::NeedsMap(options_.channel)) {
    ROS_INFO("audio_propagation: waiting up to %.0f s for /map", options_.map_timeout);
    const auto msg = ros::topic::waitForMessage<nav_msgs::OccupancyGrid>("/map", nh_, ros::Duration(options_.map_timeout));
    if (!msg) throw ParamError("no ~world, no ~map, and nothing on /map within ~map_timeout");
    map = FromOccupancyGrid(*msg);
  }
  const ros::WallTime t0 = ros::WallTime::now();
  try {
    sim_ = audio_propagation::BuildSimulatedChannel(options_.channel, std::move(map));
  } catch (const audio_propagation::ChannelOptionError& e) {
    throw OptionParamError(pnh_, e.field(), e.problem());
  }
  if (sim_.acoustic) ROS_INFO("audio_propagation: acoustic channel model, decode table %s", sim_.decode_table.c_str());
  if (sim_.acoustic && sim_.acoustic->rooms()) {
    // Latched: the rooms stand for as long as the map.
    const audio_propagation::RoomCoupling& rooms = *sim_.acoustic->rooms();
    rooms_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("rooms", 1, true);
    rooms_pub_.publish(ToRoomMarkers(rooms, sim_.propagation->map(), options_.frame_id));
    ROS_INFO("audio_propagation: coupled rooms, %zu rooms and %zu openings (~rooms)",
             rooms.segmentation().rooms().size(), rooms.segmentation().openings().size());
  }
  if (sim_.delivery_robot) delivery_pub_ = pnh_.advertise<nav_msgs::OccupancyGrid>("delivery_map", 1, true);
  const audio_propagation::PropagationModel& model = *sim_.propagation;
  ROS_INFO("audio_propagation: %zu robots, %zu diffraction points (%s), %zu corners, %zu edges, built in %.0f ms",
           sim_.robots.size(), model.diffraction_points().size(),
           audio_propagation::DiffractionRuleName(model.options().rule), model.graph().size(),
           model.graph().edge_count(), (ros::WallTime::now() - t0).toSec() * 1000.0);

  const std::size_t n = sim_.robots.size();
  last_carrier_.assign(n, false);
  carrier_published_.assign(n, -std::numeric_limits<double>::infinity());
  have_pose_.assign(n, false);
  missing_poses_.assign(n, 0);
  pose_stamps_.assign(n, ros::Time());
  for (std::size_t k = 0; k < n; ++k) {
    ros::NodeHandle rnh(nh_, sim_.robots[k]);
    tx_subs_.push_back(guard_.Subscribe<multirobot_audio::AudioPacket>(
        lockstep_, rnh, "audio/tx", 10,
        [format = sim_.format](const multirobot_audio::AudioPacket& m) {
          return PacketProblem(m, format.min_bytes, format.max_bytes);
        },
        [this, k](const multirobot_audio::AudioPacket::ConstPtr& m) { return OnTx(k, m); }));
    // (What is already in the air is settled at the next update: sleeping through silence, the
    // node is called to a step by a packet, not by the robots' poses.)
    rx_pubs_.push_back(lockstep_.Advertise<multirobot_audio::AudioReception>(rnh, "audio/rx", 50));
    carrier_pubs_.push_back(lockstep_.Advertise<multirobot_audio::CarrierSense>(rnh, "audio/carrier", 10));

    sim_.channel->SetPose(k, {kUnknown, kUnknown, 0.0});
  }
  ranging_ = std::make_unique<SimulatedRangingRos>(nh_, pnh_, lockstep_, sim_.robots, options_.ranging, options_.channel.profile,
                                                   static_cast<std::uint32_t>(options_.channel.seed));
  if (!ranging_->arrival_errors().empty()) {
    ROS_INFO("audio_propagation: ranging measured, arrival errors from %s", ranging_->arrival_errors().c_str());
  }
  if (lockstep_.enabled()) {
    // The whole team's poses in one message a step (a hundred robots' ground_truth would be a
    // hundred); passive: they alone do not call the node to a step.
    for (std::size_t k = 0; k < n; ++k) robot_index_[sim_.robots[k]] = k;
    truth_sub_ = guard_.Subscribe<multirobot_audio::RobotPoses>(
        lockstep_, nh_, options_.robot_poses, 10, RobotPosesProblem,
        [this](const multirobot_audio::RobotPoses::ConstPtr& m) { OnRobotPoses(*m); });
    lockstep_.Passive(nh_, options_.robot_poses);
  }
  paths_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("paths", 10);
  points_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("diffraction_points", 1, true);
  PublishDiffractionPoints();
  std::function<double()> rest;
  if (!options_.every_step) rest = [this] { return RestUntil(); };
  timer_ = lockstep_.CreateTimer(
      nh_, ros::Duration(1.0 / options_.update_rate), [this](const ros::TimerEvent& e) { OnTimer(e); }, rest);
  updater_.setHardwareID("none");
  updater_.add("poses", this, &AudioPropagationRos::DiagnosePoses);
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_.force_update(); });
}

AudioPropagationRos::~AudioPropagationRos() {
  // Printed directly: the node's logging is already shut down when it is destroyed.
  std::uint64_t missing = 0;
  for (const std::uint64_t m : missing_poses_) missing += m;
  std::printf("audio_propagation summary: sent %lu, heard %lu packets and %lu noise; %s; %lu packets found "
              "their robot's queue full; %lu pose look-ups failed; updates %lu (%lu of them resting); "
              "path cache %lu hits, %lu misses; corner views %lu reused, %lu worked out; %lu arrivals unheard "
              "(acoustic model); %s\n",
              static_cast<unsigned long>(sent_), static_cast<unsigned long>(packets_heard_),
              static_cast<unsigned long>(noise_heard_), guard_.Summary().c_str(),
              static_cast<unsigned long>(sim_.channel ? sim_.channel->send_overflows() : 0), static_cast<unsigned long>(missing),
              static_cast<unsigned long>(updates_), static_cast<unsigned long>(idle_updates_),
              static_cast<unsigned long>(sim_.channel ? sim_.channel->cache().hits() : 0),
              static_cast<unsigned long>(sim_.channel ? sim_.channel->cache().misses() : 0),
              static_cast<unsigned long>(sim_.channel ? sim_.channel->memo().hits() : 0),
              static_cast<unsigned long>(sim_.channel ? sim_.channel->memo().misses() : 0),
              static_cast<unsigned long>(sim_.channel ? sim_.channel->unheard() : 0),
              ranging_ ? ranging_->Summary().c_str() : "ranging not started");
  std::fflush(stdout);
}

InputGuard::Verdict AudioPropagationRos::OnTx(std::size_t robot, const multirobot_audio::AudioPacket::ConstPtr& msg) {
  // Without the lockstep the poses are not read while the node rests: read them now, so that
  // the packet leaves from where the robots are.
  if (!lockstep_.enabled() && !options_.every_step && RestUntil() > ros::Time::now().toSec()) {
    UpdatePoses(ros::Time::now());
  }
  // Stamped with the time it came: in lockstep, the step it was sent in.
  if (!sim_.channel->SendAt(robot, sim_.Frame(msg->data), ChannelTime(ros::Time::now()))) {
    return InputGuard::Verdict::Drop("the robot has too many packets waiting to enter its queue");
  }
  return InputGuard::Verdict::Accept();
}

void AudioPropagationRos::DiagnosePoses(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::string missing;
  const ros::Time now = ros::Time::now();
  for (std::size_t k = 0; k < sim_.robots.size(); ++k) {
    char text[128];
    if (have_pose_[k]) {
      std::snprintf(text, sizeof text, "pose %.1f s old, %lu look-ups failed", (now - pose_stamps_[k]).toSec(),
                    static_cast<unsigned long>(missing_poses_[k]));
    } else {
      std::snprintf(text, sizeof text, "no pose yet, %lu look-ups failed", static_cast<unsigned long>(missing_poses_[k]));
      missing += (missing.empty() ? "" : ", ") + sim_.robots[k];
    }
    status.add(sim_.robots[k], text);
  }
  if (missing.empty()) {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "every robot's pose known");
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no pose (neither heard nor heard from): " + missing);
  }
}

double AudioPropagationRos::ChannelTime(const ros::Time& t) {
  if (start_.isZero()) start_ = ros::Time::now();
  return (t - start_).toSec();
}

void AudioPropagationRos::CheckInside(std::size_t robot, const grid::Pose2D& pose) const {
  if (!sim_.propagation->map().IsFreeAt(pose.position())) {
    ROS_WARN_THROTTLE(5.0, "audio_propagation: %s is inside a wall or off the map at (%.2f, %.2f): it neither hears nor is heard",
                      sim_.robots[robot].c_str(), pose.x, pose.y);
  }
}

void AudioPropagationRos::OnRobotPoses(const multirobot_audio::RobotPoses& msg) {
  // Stamped when the world took them (never later than now: a stamp from the future would hold
  // the robots back).
  const ros::Time now = ros::Time::now();
  const ros::Time stamp = msg.header.stamp.isZero() ? now : std::min(msg.header.stamp, now);
  const double t = ChannelTime(stamp);
  for (std::size_t i = 0; i < msg.names.size(); ++i) {
    const auto it = robot_index_.find(msg.names[i]);
    if (it == robot_index_.end()) continue;  // a robot of the world this node does not serve
    const std::size_t k = it->second;
    const grid::Pose2D pose{msg.poses[i].x, msg.poses[i].y, msg.poses[i].theta};
    CheckInside(k, pose);
    sim_.channel->SetPoseAt(k, pose, t);
    pose_stamps_[k] = stamp;
    have_pose_[k] = true;
  }
}

void AudioPropagationRos::UpdatePoses(const ros::Time& now) {
  for (std::size_t k = 0; k < sim_.robots.size(); ++k) {
    const std::string frame = sim_.robots[k] + "/base_link";
    try {
      const auto t = tf_buffer_.lookupTransform(options_.frame_id, frame, ros::Time(0));
      const grid::Pose2D pose{t.transform.translation.x, t.transform.translation.y, FromQuaternionYaw(t.transform.rotation)};
      pose_stamps_[k] = t.header.stamp;
      CheckInside(k, pose);
      sim_.channel->SetPoseAt(k, pose, ChannelTime(now));
      have_pose_[k] = true;
    } catch (const tf2::TransformException& e) {
      ++missing_poses_[k];
      if (!have_pose_[k]) {
        ROS_WARN_THROTTLE(5.0, "audio_propagation: no pose for %s yet (%s)", sim_.robots[k].c_str(), e.what());
      }
    }
  }
}

double AudioPropagationRos::RestUntil() const {
  if (start_.isZero()) return 0.0;
  // Until the channel may have something to publish, or a carrier is to be repeated.
  double next = sim_.channel->NextEventTime();
  for (const double t : carrier_published_) next = std::min(next, t + options_.carrier_refresh);
  if (delivery_pub_) next = std::min(next, next_delivery_map_);
  if (ranging_) next = std::min(next, ranging_->next_publish());
  // (A hair early rather than a step late: the step's time and the channel's ticks are rounded
  // differently.)
  return start_.toSec() + next - 1e-6;
}

void AudioPropagationRos::OnTimer(const ros::TimerEvent& event) {
  const ros::Time now = event.current_real;
  const double t = ChannelTime(now);
  ++updates_;
  if (!lockstep_.enabled()) {
    // Poses are only read when they matter: with nothing to report before the next update, an
    // update is a few comparisons (a team of a hundred robots at 100 Hz would otherwise cost
    // 10^4 look-ups a second for nothing).
    if (options_.every_step || RestUntil() <= now.toSec()) {
      UpdatePoses(now);
    } else {
      ++idle_updates_;
    }
  }
  const auto events = sim_.channel->AdvanceTo(t);

  sent_ += events.started.size();
  const visualization_msgs::MarkerArray paths =
      ToSoundPathMarkers(events.started, sim_.robots, sim_.propagation->options(), options_.path_display_time,
                         options_.frame_id, now, marker_id_);
  marker_id_ += static_cast<int>(paths.markers.size());
  if (!paths.markers.empty()) paths_pub_.publish(paths);
  if (delivery_pub_ && sim_.channel->time() >= next_delivery_map_ && have_pose_[*sim_.delivery_robot]) {
    next_delivery_map_ = sim_.channel->time() + options_.delivery_map_period;
    PublishDeliveryMap(now);
  }

  // In time order, the transmissions at their start and the receptions at their end: each
  // robot's timings then go forward on its clock, as its sound card's do.
  std::size_t next_started = 0;
  for (const auto& rx : events.received) {
    while (next_started < events.started.size() && events.started[next_started].start <= rx.time) {
      ranging_->Started(events.started[next_started++]);
    }
    if (rx.kind == audio_propagation::Reception::Kind::kPacket) {
      ++packets_heard_;
    } else {
      ++noise_heard_;
    }
    multirobot_audio::AudioReception msg =
        ToAudioReception(rx, sim_.robots[rx.receiver] + "/base_link", start_ + ros::Duration(rx.time));
    ranging_->Received(rx, msg);
    rx_pubs_[rx.receiver].publish(msg);
  }
  while (next_started < events.started.size()) ranging_->Started(events.started[next_started++]);
  ranging_->PublishDue(sim_.channel->time(), now);

  PublishCarriers(now);
}

void AudioPropagationRos::PublishCarriers(const ros::Time& now) {
  // On every change, and again every ~carrier_refresh s so that late subscribers learn the state.
  const double t = sim_.channel->time();
  for (std::size_t k = 0; k < sim_.robots.size(); ++k) {
    const bool carrier = sim_.channel->Carrier(k);
    if (carrier == last_carrier_[k] && t < carrier_published_[k] + options_.carrier_refresh) continue;
    last_carrier_[k] = carrier;
    carrier_published_[k] = t;
    multirobot_audio::CarrierSense msg;
    msg.header.stamp = now;
    msg.header.frame_id = sim_.robots[k] + "/base_link";
    msg.carrier = carrier;
    msg.level_db = static_cast<float>(sim_.channel->Level(k));
    carrier_pubs_[k].publish(msg);
  }
}

void AudioPropagationRos::PublishDeliveryMap(const ros::Time& now) {
  std::vector<Eigen::Vector2d> robots(sim_.robots.size());
  for (std::size_t k = 0; k < robots.size(); ++k) robots[k] = sim_.channel->pose(k).position();
  const audio_propagation::DeliveryMap d = audio_propagation::MapDelivery(
      *sim_.acoustic, robots[*sim_.delivery_robot], sim_.channel->time(), robots, options_.delivery_map_resolution);
  delivery_pub_.publish(ToOccupancyGrid(d, options_.frame_id, now));
}

void AudioPropagationRos::PublishDiffractionPoints() {
  const audio_propagation::PropagationModel& model = *sim_.propagation;
  std::vector<Eigen::Vector2d> corners;
  for (std::size_t k = 0; k < model.graph().size(); ++k) {
    corners.push_back(model.map().CellCoordsToWorld(model.graph().position(k)));
  }
  points_pub_.publish(ToDiffractionPointMarkers(corners, options_.frame_id));
}

}  // namespace multirobot_audio
