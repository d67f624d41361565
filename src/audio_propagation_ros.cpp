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
#include "input_checks.h"
#include "audio_propagation/delivery_map.h"
#include "audio_propagation/decode_table.h"
#include "params.h"
#include "grid/map_file.h"
#include "nava_modem/modem_profile.h"
#include "world_sim/world_file.h"

namespace multirobot_audio {
namespace {

constexpr double kUnknown = -1e6;  // where a robot with no pose yet is put: off every map

geometry_msgs::Point ToPoint(const Eigen::Vector2d& p, double z) {
  geometry_msgs::Point out;
  out.x = p.x();
  out.y = p.y();
  out.z = z;
  return out;
}

}  // namespace

AudioPropagationOptions ReadAudioPropagationOptions(const ros::NodeHandle& pnh) {
  AudioPropagationOptions o;
  o.world_file = StringParam(pnh, "world", "");
  o.map_file = StringParam(pnh, "map", "");
  o.map_timeout = NumberParam(pnh, "map_timeout", o.map_timeout, 0.0, 1e6);
  if (pnh.hasParam("robots") && !pnh.getParam("robots", o.robots)) {
    throw ParamError(pnh.resolveName("robots") + ": expected a list of robot names");
  }
  if (o.world_file.empty() && o.robots.empty()) {
    throw ParamError(pnh.resolveName("robots") + ": required (a list of robot names) when ~world is not set");
  }
  if (pnh.hasParam("microphones") && !pnh.getParam("microphones", o.microphones)) {
    throw ParamError(pnh.resolveName("microphones") + ": expected a list of omni, bidirectional or none");
  }
  o.update_rate = NumberParam(pnh, "update_rate", o.update_rate, 1.0, 10000.0);
  const std::string update = StringParam(pnh, "update", "events");
  if (update != "events" && update != "every_step") {
    throw ParamError(pnh.resolveName("update") + ": expected events or every_step, got '" + update + "'");
  }
  o.every_step = update == "every_step";
  o.carrier_refresh = NumberParam(pnh, "carrier_refresh", o.carrier_refresh, 0.01, 3600.0);
  o.path_display_time = NumberParam(pnh, "path_display_time", o.path_display_time, 0.0, 3600.0);
  o.packet_bytes = IntParam(pnh, "packet_bytes", o.packet_bytes, 1, 1024);
  auto& m = o.model;
  m.source_level_db = NumberParam(pnh, "source_level_db", m.source_level_db, -1000.0, 1000.0);
  o.threshold_given = pnh.hasParam("threshold_db");
  m.threshold_db = NumberParam(pnh, "threshold_db", m.threshold_db, -1000.0, 1000.0);
  if (m.threshold_db > m.source_level_db) {
    throw ParamError(pnh.resolveName("threshold_db") + ": expected at most ~source_level_db (" +
                     std::to_string(m.source_level_db) + "), got " + std::to_string(m.threshold_db));
  }
  m.max_range = NumberParam(pnh, "max_range", m.max_range, 0.0, 1e6);
  m.speed_of_sound = NumberParam(pnh, "speed_of_sound", m.speed_of_sound, 1.0, 1e5);
  const std::string rule = StringParam(pnh, "rule", "masks");
  const auto parsed = audio_propagation::ParseDiffractionRule(rule);
  if (!parsed) throw ParamError(pnh.resolveName("rule") + ": expected masks or convex_corners, got '" + rule + "'");
  m.rule = *parsed;
  auto& c = o.channel;
  c.capture_margin_db = NumberParam(pnh, "capture_margin_db", c.capture_margin_db, 0.0, 1000.0);
  c.direction_noise = NumberParam(pnh, "direction_noise", c.direction_noise, 0.0, 10.0);
  // The modem profile the robots run sets how long a packet sounds (and the MAC's unit of time).
  const std::string profile = StringParam(pnh, "profile", "nava");
  o.profile = profile;
  o.channel_model = StringParam(pnh, "channel_model", o.channel_model);
  if (o.channel_model != "threshold" && o.channel_model != "acoustic") {
    throw ParamError(pnh.resolveName("channel_model") + ": expected threshold or acoustic, got '" + o.channel_model + "'");
  }
  o.decode_table = StringParam(pnh, "decode_table", "");
  o.robot_poses = StringParam(pnh, "robot_poses", o.robot_poses);
  o.delivery_map_robot = StringParam(pnh, "delivery_map_robot", "");
  o.delivery_map_period = NumberParam(pnh, "delivery_map_period", o.delivery_map_period, 0.1, 1e6);
  o.delivery_map_resolution = NumberParam(pnh, "delivery_map_resolution", o.delivery_map_resolution, 0.01, 100.0);
  if (o.channel_model != "acoustic" && (!o.decode_table.empty() || !o.delivery_map_robot.empty())) {
    throw ParamError(pnh.resolveName(o.decode_table.empty() ? "delivery_map_robot" : "decode_table") +
                     ": only used by ~channel_model acoustic");
  }
  const auto parsed_profile = nava_modem::ParseProfile(profile);
  if (!parsed_profile) {
    throw ParamError(pnh.resolveName("profile") + ": expected " + nava_modem::kProfileNames + ", got '" + profile + "'");
  }
  if (*parsed_profile == nava_modem::Profile::kNava) {
    nava_modem::ModemOptions modem;
    modem.baud = NumberParam(pnh, "bit_rate", modem.baud, 1.0, 100000.0);
    nava_modem::UseProfileTiming(*parsed_profile, modem, c.mac);
  } else {
    if (pnh.hasParam("bit_rate")) {
      throw ParamError(pnh.resolveName("bit_rate") + ": sets the nava profile's bit rate; profile " + profile + " has its own timing");
    }
    nava_modem::UseProfileTiming(*parsed_profile, {}, c.mac);
  }
  c.seed = static_cast<std::uint32_t>(IntParam(pnh, "seed", 1, 0, 2147483647));
  c.cache_size = static_cast<std::size_t>(IntParam(pnh, "cache_size", 1000, 0, 10000000));
  try {
    nava_modem::ValidateMacOptions(c.mac);
    audio_propagation::ValidateOptions(m);
  } catch (const std::invalid_argument& e) {
    throw ParamError(e.what());
  }
  return o;
}

AudioPropagationRos::AudioPropagationRos(ros::NodeHandle nh, ros::NodeHandle pnh,
                                         const AudioPropagationOptions& options)
    : nh_(nh), pnh_(pnh), lockstep_(nh), updater_(nh, pnh), guard_(updater_), options_(options),
      tf_listener_(lockstep_.enabled() ? nullptr : std::make_unique<tf2_ros::TransformListener>(tf_buffer_)) {
  grid::OccupancyMap map;
  std::vector<world_sim::RobotSpec> specs;
  std::optional<world_sim::Acoustics> acoustics;
  if (!options_.world_file.empty()) {
    world_sim::LoadedWorld world = world_sim::LoadWorldFile(options_.world_file, options_.map_file);
    map = std::move(world.map);
    specs = world.config.robots;
    acoustics = world.config.acoustics;
  } else if (!options_.map_file.empty()) {
    map = grid::LoadMapFile(options_.map_file);
  } else {
    ROS_INFO("audio_propagation: waiting up to %.0f s for /map", options_.map_timeout);
    const auto msg = ros::topic::waitForMessage<nav_msgs::OccupancyGrid>("/map", nh_, ros::Duration(options_.map_timeout));
    if (!msg) throw ParamError("no ~world, no ~map, and nothing on /map within ~map_timeout");
    map = FromOccupancyGrid(*msg);
  }
  if (options_.robots.empty()) {
    for (const auto& r : specs) options_.robots.push_back(r.name);
  }
  for (const std::string& name : options_.robots) {
    const auto it = std::find_if(specs.begin(), specs.end(),
                                 [&](const world_sim::RobotSpec& r) { return r.name == name; });
    if (it == specs.end() && !options_.world_file.empty()) {
      throw ParamError(pnh_.resolveName("robots") + ": robot '" + name + "' is not in " + options_.world_file);
    }
    microphones_.push_back(it == specs.end() ? world_sim::Microphone::kOmni : it->microphone);
  }
  if (!options_.microphones.empty()) {
    if (options_.microphones.size() != options_.robots.size()) {
      throw ParamError(pnh_.resolveName("microphones") + ": expected one entry per robot (" +
                       std::to_string(options_.robots.size()) + "), got " +
                       std::to_string(options_.microphones.size()));
    }
    for (std::size_t k = 0; k < microphones_.size(); ++k) {
      const auto mic = world_sim::ParseMicrophone(options_.microphones[k]);
      if (!mic) {
        throw ParamError(pnh_.resolveName("microphones") + "[" + std::to_string(k) +
                         "]: expected omni, bidirectional or none, got '" + options_.microphones[k] + "'");
      }
      microphones_[k] = *mic;
    }
  }
  if (options_.channel_model == "acoustic" && acoustics && !options_.threshold_given) {
    // Paths to every listener the model might judge audible, not only those above 40 dB.
    options_.model.threshold_db = std::min(options_.model.source_level_db,
                                           audio_propagation::AcousticThresholdDb(*acoustics));
  }
  const ros::WallTime t0 = ros::WallTime::now();
  model_ = std::make_unique<audio_propagation::PropagationModel>(std::move(map), options_.model);
  if (options_.channel_model == "acoustic") {
    if (!acoustics) {
      throw ParamError(pnh_.resolveName("channel_model") + ": acoustic needs a world file (~world) with an acoustics section; " +
                       (options_.world_file.empty() ? std::string("no ~world is set") : options_.world_file + " has none"));
    }
    const std::string table = options_.decode_table.empty() ? audio_propagation::ShippedDecodeTable(options_.profile)
                                                            : options_.decode_table;
    try {
      acoustic_ = std::make_unique<audio_propagation::AcousticModel>(
          *model_, *acoustics, audio_propagation::LoadDecodeTable(table, options_.profile), options_.robots);
    } catch (const std::invalid_argument& e) {
      throw ParamError(options_.world_file + ": " + e.what());
    }
    if (!options_.delivery_map_robot.empty()) {
      const auto it = std::find(options_.robots.begin(), options_.robots.end(), options_.delivery_map_robot);
      if (it == options_.robots.end()) {
        throw ParamError(pnh_.resolveName("delivery_map_robot") + ": no robot named '" + options_.delivery_map_robot + "'");
      }
      delivery_robot_ = static_cast<std::size_t>(it - options_.robots.begin());
      delivery_pub_ = pnh_.advertise<nav_msgs::OccupancyGrid>("delivery_map", 1, true);
    }
    ROS_INFO("audio_propagation: acoustic channel model, decode table %s", table.c_str());
  }
  channel_ = std::make_unique<audio_propagation::AudioChannel>(*model_, microphones_, options_.channel, acoustic_.get());
  ROS_INFO("audio_propagation: %zu robots, %zu diffraction points (%s), %zu corners, %zu edges, built in %.0f ms",
           options_.robots.size(), model_->diffraction_points().size(),
           audio_propagation::DiffractionRuleName(options_.model.rule), model_->graph().size(),
           model_->graph().edge_count(), (ros::WallTime::now() - t0).toSec() * 1000.0);

  const std::size_t n = options_.robots.size();
  last_carrier_.assign(n, false);
  carrier_published_.assign(n, -std::numeric_limits<double>::infinity());
  have_pose_.assign(n, false);
  missing_poses_.assign(n, 0);
  pose_stamps_.assign(n, ros::Time());
  const std::size_t packet_bytes = static_cast<std::size_t>(options_.packet_bytes);
  for (std::size_t k = 0; k < n; ++k) {
    ros::NodeHandle rnh(nh_, options_.robots[k]);
    tx_subs_.push_back(guard_.Subscribe<multirobot_audio::AudioPacket>(
        lockstep_, rnh, "audio/tx", 10,
        [packet_bytes](const multirobot_audio::AudioPacket& m) { return PacketProblem(m, packet_bytes); },
        [this, k](const multirobot_audio::AudioPacket::ConstPtr& m) { return OnTx(k, m); }));
    // (What is already in the air is settled at the next update: sleeping through silence, the
    // node is called to a step by a packet, not by the robots' poses.)
    rx_pubs_.push_back(lockstep_.Advertise<multirobot_audio::AudioReception>(rnh, "audio/rx", 50));
    carrier_pubs_.push_back(lockstep_.Advertise<multirobot_audio::CarrierSense>(rnh, "audio/carrier", 10));

    channel_->SetPose(k, {kUnknown, kUnknown, 0.0});
  }
  if (lockstep_.enabled()) {
    // The whole team's poses in one message a step (a hundred robots' ground_truth would be a
    // hundred); passive: they alone do not call the node to a step.
    for (std::size_t k = 0; k < n; ++k) robot_index_[options_.robots[k]] = k;
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
              "path cache %lu hits, %lu misses; %lu arrivals unheard (acoustic model)\n",
              static_cast<unsigned long>(sent_), static_cast<unsigned long>(packets_heard_),
              static_cast<unsigned long>(noise_heard_), guard_.Summary().c_str(),
              static_cast<unsigned long>(channel_ ? channel_->send_overflows() : 0), static_cast<unsigned long>(missing),
              static_cast<unsigned long>(updates_), static_cast<unsigned long>(idle_updates_),
              static_cast<unsigned long>(channel_ ? channel_->cache().hits() : 0),
              static_cast<unsigned long>(channel_ ? channel_->cache().misses() : 0),
              static_cast<unsigned long>(channel_ ? channel_->unheard() : 0));
  std::fflush(stdout);
}

InputGuard::Verdict AudioPropagationRos::OnTx(std::size_t robot, const multirobot_audio::AudioPacket::ConstPtr& msg) {
  // Without the lockstep the poses are not read while the node rests: read them now, so that
  // the packet leaves from where the robots are.
  if (!lockstep_.enabled() && !options_.every_step && RestUntil() > ros::Time::now().toSec()) {
    UpdatePoses(ros::Time::now());
  }
  // Stamped with the time it came: in lockstep, the step it was sent in.
  if (!channel_->SendAt(robot, msg->data, ChannelTime(ros::Time::now()))) {
    return InputGuard::Verdict::Drop("the robot has too many packets waiting to enter its queue");
  }
  return InputGuard::Verdict::Accept();
}

void AudioPropagationRos::DiagnosePoses(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::string missing;
  const ros::Time now = ros::Time::now();
  for (std::size_t k = 0; k < options_.robots.size(); ++k) {
    char text[128];
    if (have_pose_[k]) {
      std::snprintf(text, sizeof text, "pose %.1f s old, %lu look-ups failed", (now - pose_stamps_[k]).toSec(),
                    static_cast<unsigned long>(missing_poses_[k]));
    } else {
      std::snprintf(text, sizeof text, "no pose yet, %lu look-ups failed", static_cast<unsigned long>(missing_poses_[k]));
      missing += (missing.empty() ? "" : ", ") + options_.robots[k];
    }
    status.add(options_.robots[k], text);
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
  if (!model_->map().IsFreeAt(pose.position())) {
    ROS_WARN_THROTTLE(5.0, "audio_propagation: %s is inside a wall or off the map at (%.2f, %.2f): it neither hears nor is heard",
                      options_.robots[robot].c_str(), pose.x, pose.y);
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
    channel_->SetPoseAt(k, pose, t);
    pose_stamps_[k] = stamp;
    have_pose_[k] = true;
  }
}

void AudioPropagationRos::UpdatePoses(const ros::Time& now) {
  for (std::size_t k = 0; k < options_.robots.size(); ++k) {
    const std::string frame = options_.robots[k] + "/base_link";
    try {
      const auto t = tf_buffer_.lookupTransform("map", frame, ros::Time(0));
      const grid::Pose2D pose{t.transform.translation.x, t.transform.translation.y, FromQuaternionYaw(t.transform.rotation)};
      pose_stamps_[k] = t.header.stamp;
      CheckInside(k, pose);
      channel_->SetPoseAt(k, pose, ChannelTime(now));
      have_pose_[k] = true;
    } catch (const tf2::TransformException& e) {
      ++missing_poses_[k];
      if (!have_pose_[k]) {
        ROS_WARN_THROTTLE(5.0, "audio_propagation: no pose for %s yet (%s)", options_.robots[k].c_str(), e.what());
      }
    }
  }
}

double AudioPropagationRos::RestUntil() const {
  if (start_.isZero()) return 0.0;
  // Until the channel may have something to publish, or a carrier is to be repeated.
  double next = channel_->NextEventTime();
  for (const double t : carrier_published_) next = std::min(next, t + options_.carrier_refresh);
  if (delivery_pub_) next = std::min(next, next_delivery_map_);
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
  const auto events = channel_->AdvanceTo(t);

  visualization_msgs::MarkerArray paths;
  for (const auto& tx : events.started) {
    ++sent_;
    for (std::size_t r = 0; r < tx.paths.size(); ++r) {
      const auto& p = tx.paths[r];
      // Acoustic model: every path with a chance of being decoded, green (sure) to red (hopeless).
      const bool acoustic = !tx.probability.empty();
      if (acoustic ? tx.probability[r] < 0.01 : !p.audible) continue;
      visualization_msgs::Marker m;
      m.header.frame_id = "map";
      m.header.stamp = now;
      m.ns = options_.robots[tx.sender];
      m.id = marker_id_++;
      m.type = visualization_msgs::Marker::LINE_STRIP;
      m.action = visualization_msgs::Marker::ADD;
      m.pose.orientation.w = 1.0;
      m.scale.x = 0.04;
      m.lifetime = ros::Duration(std::max(tx.duration, options_.path_display_time));
      if (acoustic) {
        const float sure = static_cast<float>(tx.probability[r]);
        m.color.r = 1.0f - sure;
        m.color.g = sure;
        m.color.b = 0.1f;
      } else {  // loud is red, barely audible is blue
        const double span = options_.model.source_level_db - options_.model.threshold_db;
        const float loud = static_cast<float>(std::clamp((p.level_db - options_.model.threshold_db) / span, 0.0, 1.0));
        m.color.r = loud;
        m.color.b = 1.0f - loud;
        m.color.g = 0.2f;
      }
      m.color.a = 0.9f;
      for (const auto& q : p.polyline) m.points.push_back(ToPoint(q, 0.15));
      paths.markers.push_back(m);
    }
  }
  if (!paths.markers.empty()) paths_pub_.publish(paths);
  if (delivery_pub_ && channel_->time() >= next_delivery_map_ && have_pose_[delivery_robot_]) {
    next_delivery_map_ = channel_->time() + options_.delivery_map_period;
    PublishDeliveryMap(now);
  }

  for (const auto& rx : events.received) {
    if (rx.kind == audio_propagation::Reception::Kind::kPacket) {
      ++packets_heard_;
    } else {
      ++noise_heard_;
    }
    const multirobot_audio::AudioReception msg =
        ToAudioReception(rx, options_.robots[rx.receiver] + "/base_link", start_ + ros::Duration(rx.time));
    rx_pubs_[rx.receiver].publish(msg);
  }

  PublishCarriers(now);
}

void AudioPropagationRos::PublishCarriers(const ros::Time& now) {
  // On every change, and again every ~carrier_refresh s so that late subscribers learn the state.
  const double t = channel_->time();
  for (std::size_t k = 0; k < options_.robots.size(); ++k) {
    const bool carrier = channel_->Carrier(k);
    if (carrier == last_carrier_[k] && t < carrier_published_[k] + options_.carrier_refresh) continue;
    last_carrier_[k] = carrier;
    carrier_published_[k] = t;
    multirobot_audio::CarrierSense msg;
    msg.header.stamp = now;
    msg.header.frame_id = options_.robots[k] + "/base_link";
    msg.carrier = carrier;
    msg.level_db = static_cast<float>(channel_->Level(k));
    carrier_pubs_[k].publish(msg);
  }
}

void AudioPropagationRos::PublishDeliveryMap(const ros::Time& now) {
  std::vector<Eigen::Vector2d> robots(options_.robots.size());
  for (std::size_t k = 0; k < robots.size(); ++k) robots[k] = channel_->pose(k).position();
  const audio_propagation::DeliveryMap d = audio_propagation::MapDelivery(
      *acoustic_, robots[delivery_robot_], channel_->time(), robots, options_.delivery_map_resolution);
  delivery_pub_.publish(ToOccupancyGrid(d, "map", now));
}

void AudioPropagationRos::PublishDiffractionPoints() {
  visualization_msgs::MarkerArray out;
  visualization_msgs::Marker m;
  m.header.frame_id = "map";
  m.ns = "corners";
  m.id = 0;
  m.type = visualization_msgs::Marker::POINTS;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = 0.08;
  m.color.g = 0.8f;
  m.color.r = 0.2f;
  m.color.a = 1.0f;
  for (std::size_t k = 0; k < model_->graph().size(); ++k) {
    m.points.push_back(ToPoint(model_->map().CellCoordsToWorld(model_->graph().position(k)), 0.05));
  }
  out.markers.push_back(m);
  points_pub_.publish(out);
}

}  // namespace multirobot_audio
