#include "ranging_ros.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "nava_modem/room_frame.h"
#include "params.h"

namespace multirobot_audio {
namespace {

ranging::Timing FromMsg(const multirobot_audio::PacketTiming& m) {
  ranging::Timing t;
  t.sender = m.sender;
  t.listener = m.listener;
  t.data = m.data;
  t.arrival = m.arrival;
  t.rate_error = m.rate_error;
  t.clock_epoch = m.clock_epoch;
  t.stamp = m.heard.isZero() ? std::numeric_limits<double>::quiet_NaN() : m.heard.toSec();
  return t;
}

multirobot_audio::PacketTiming ToMsg(const ranging::Timing& t) {
  multirobot_audio::PacketTiming m;
  m.sender = t.sender;
  m.listener = t.listener;
  m.data = t.data;
  m.arrival = t.arrival;
  m.rate_error = t.rate_error;
  m.clock_epoch = t.clock_epoch;
  if (std::isfinite(t.stamp) && t.stamp > 0.0) m.heard = ros::Time(t.stamp);
  return m;
}

}  // namespace

RangingRosOptions ReadRangingRosOptions(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  RangingRosOptions o;
  std::string robot = nh.getNamespace();
  while (!robot.empty() && robot.front() == '/') robot.erase(robot.begin());
  o.robot = StringParam(pnh, "robot", robot);
  if (o.robot.empty()) throw ParamError(pnh.resolveName("robot") + ": expected this robot's name (the node runs in no namespace)");
  o.team = StringListParam(pnh, "team", "a list of the team's robot names");
  o.timings_topic = StringParam(pnh, "timings_topic", o.timings_topic);
  o.teammates_rate = NumberParam(pnh, "teammates_rate", o.teammates_rate, 0.01, 100.0);
  o.ranger = ReadRangerParams(pnh, o.ranger, true);
  return o;
}

ranging::RangerOptions ReadRangerParams(const ros::NodeHandle& pnh, ranging::RangerOptions r, bool read_speed) {
  std::vector<std::string> fields = {"ranging_window", "ranging_samples", "ranging_offset"};
  if (read_speed) {
    r.speed_of_sound = NumberParam(pnh, "speed_of_sound", r.speed_of_sound);
    fields.push_back("speed_of_sound");
  }
  r.pair_window = NumberParam(pnh, "ranging_window", r.pair_window);
  r.samples = IntParam(pnh, "ranging_samples", r.samples);
  r.offset = NumberParam(pnh, "ranging_offset", r.offset);
  CheckOptionParams(pnh, fields, [&] {
    try {
      ranging::ValidateRangerOptions(r);
    } catch (const std::invalid_argument& e) {
      // The ranger names its fields; the parameters have a prefix of their own.
      std::string what = e.what();
      for (const auto& [field, param] : std::vector<std::pair<std::string, std::string>>{
               {"pair_window", "ranging_window"}, {"samples", "ranging_samples"}, {"offset", "ranging_offset"}}) {
        const auto at = what.find("ranger " + field + " ");
        if (at != std::string::npos) what.replace(at, 7 + field.size(), param);
      }
      throw std::invalid_argument(what);
    }
  });
  return r;
}

multirobot_audio::Teammates ToTeammatesMsg(const std::vector<ranging::TeammateView>& view, const std::string& frame_id,
                                           const ros::Time& stamp) {
  multirobot_audio::Teammates msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id;
  for (const ranging::TeammateView& v : view) {
    multirobot_audio::Teammate t;
    t.name = v.name;
    t.range = t.range_std = t.range_age = t.bearing = t.bearing_age = kNan;
    if (v.range) {
      t.range = static_cast<float>(v.range->range);
      t.range_std = static_cast<float>(v.range->range_std);
      t.range_age = static_cast<float>(v.range->age);
      t.range_samples = static_cast<std::uint32_t>(v.range->samples);
    }
    if (v.bearing) {
      t.bearing = static_cast<float>(v.bearing->bearing);
      t.bearing_confidence = static_cast<float>(v.bearing->confidence);
      t.bearing_age = static_cast<float>(v.bearing_age);
    }
    msg.teammates.push_back(t);
  }
  return msg;
}

namespace {

// One robot's teammates as markers in its frame, namespace `ns`, appended to `out`.
void AppendTeammateMarkers(const std::string& ns, const multirobot_audio::Teammates& msg,
                           visualization_msgs::MarkerArray& out) {
  int id = 0;
  // A marker of `type`, numbered in turn (by value: the caller appends it once it is whole).
  const auto marker = [&](std::uint8_t type) {
    visualization_msgs::Marker m;
    m.header = msg.header;
    m.ns = ns;
    m.id = id++;
    m.type = type;
    m.action = visualization_msgs::Marker::ADD;
    m.pose.orientation.w = 1.0;
    m.color.r = 0.2f, m.color.g = 0.6f, m.color.b = 1.0f, m.color.a = 0.8f;
    return m;
  };
  for (const multirobot_audio::Teammate& t : msg.teammates) {
    const bool range = std::isfinite(t.range), bearing = std::isfinite(t.bearing);
    if (range && bearing) {
      geometry_msgs::Point at;
      at.x = t.range * std::cos(t.bearing);
      at.y = t.range * std::sin(t.bearing);
      at.z = 0.05;
      visualization_msgs::Marker disc = marker(visualization_msgs::Marker::CYLINDER);
      disc.pose.position = at;
      disc.scale.x = disc.scale.y = 2.0 * std::max(0.05, static_cast<double>(t.range_std));
      disc.scale.z = 0.02;
      disc.color.a = static_cast<float>(0.3 + 0.6 * std::clamp(static_cast<double>(t.bearing_confidence), 0.0, 1.0));
      out.markers.push_back(disc);
      visualization_msgs::Marker label = marker(visualization_msgs::Marker::TEXT_VIEW_FACING);
      label.pose.position = at;
      label.pose.position.z = 0.35;
      label.scale.z = 0.35;
      label.text = t.name + " " + std::to_string(static_cast<int>(std::lround(t.range * 100.0))) + " cm";
      out.markers.push_back(label);
      // Whose estimate it is: a faint line from the robot to it.
      visualization_msgs::Marker line = marker(visualization_msgs::Marker::LINE_STRIP);
      line.points = {geometry_msgs::Point(), at};
      line.scale.x = 0.03;
      line.color.a = 0.35f;
      out.markers.push_back(line);
    } else if (range) {
      visualization_msgs::Marker ring = marker(visualization_msgs::Marker::LINE_STRIP);
      constexpr int kSegments = 72;
      for (int k = 0; k <= kSegments; ++k) {
        geometry_msgs::Point p;
        p.x = t.range * std::cos(2.0 * M_PI * k / kSegments);
        p.y = t.range * std::sin(2.0 * M_PI * k / kSegments);
        p.z = 0.05;
        ring.points.push_back(p);
      }
      ring.scale.x = std::max(0.02, 2.0 * static_cast<double>(t.range_std));
      ring.color.a = 0.4f;
      out.markers.push_back(ring);
    } else if (bearing) {
      visualization_msgs::Marker arrow = marker(visualization_msgs::Marker::ARROW);
      geometry_msgs::Point tail, head;
      head.x = std::cos(t.bearing);
      head.y = std::sin(t.bearing);
      arrow.points = {tail, head};
      arrow.scale.x = 0.03, arrow.scale.y = 0.07, arrow.scale.z = 0.1;
      out.markers.push_back(arrow);
    }
  }
}

}  // namespace

visualization_msgs::MarkerArray ToTeammateMarkers(
    const std::vector<std::pair<std::string, multirobot_audio::Teammates>>& robots) {
  visualization_msgs::MarkerArray out;
  if (robots.empty()) return out;
  // (rviz's DELETEALL clears the whole display, whatever its namespace: one for all robots.)
  visualization_msgs::Marker clear;
  clear.header = robots.front().second.header;
  clear.action = visualization_msgs::Marker::DELETEALL;
  out.markers.push_back(clear);
  for (const auto& [ns, msg] : robots) AppendTeammateMarkers(ns, msg, out);
  return out;
}

std::string PacketTimingProblem(const multirobot_audio::PacketTiming& m, std::size_t min_bytes, std::size_t max_bytes) {
  if (m.sender.empty()) return "sender is empty";
  if (m.listener.empty()) return "listener is empty";
  if (m.data.size() < min_bytes || m.data.size() > max_bytes) {
    return "data has " + std::to_string(m.data.size()) + " bytes, expected " + std::to_string(min_bytes) +
           (min_bytes == max_bytes ? "" : " to " + std::to_string(max_bytes));
  }
  if (std::isinf(m.arrival) || (std::isnan(m.arrival) && m.sender != m.listener)) {
    return "arrival = " + std::to_string(m.arrival) + " (NaN only in a sender's announcement)";
  }
  if (!std::isfinite(m.rate_error)) return "rate_error = " + std::to_string(m.rate_error);
  return "";
}

RangingRos::RangingRos(ros::NodeHandle nh, const RangingRosOptions& options, InputGuard& guard, const std::string& frame_id)
    : options_(options), frame_id_(frame_id), ranger_(options.robot, options.team, options.ranger) {
  timings_pub_ = nh.advertise<multirobot_audio::PacketTiming>(options_.timings_topic, 100);
  teammates_pub_ = nh.advertise<multirobot_audio::Teammates>("audio/teammates", 10, true);
  markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("audio/teammates_markers", 2);
  timings_sub_ = guard.Subscribe<multirobot_audio::PacketTiming>(
      nh, options_.timings_topic, 200, [](const multirobot_audio::PacketTiming& m) {
        // A timing names its frame by the frame's bytes: any length a profile carries.
        return PacketTimingProblem(m, nava_modem::room_frame::kMinBytes, nava_modem::room_frame::kMaxBytes);
      },
      [this](const multirobot_audio::PacketTiming::ConstPtr& m) { return OnTiming(m); });
  timer_ = nh.createWallTimer(ros::WallDuration(1.0 / options_.teammates_rate), [this](const ros::WallTimerEvent&) { PublishTeammates(); });
}

// Called from the audio thread only, so that the reports' stamps go forward.
void RangingRos::Share(multirobot_audio::PacketTiming msg) {
  msg.header.stamp = ros::Time::now();
  timings_pub_.publish(msg);
  ++shared_;
}

void RangingRos::Announce(const std::vector<std::uint8_t>& data) {
  ranging::Timing t;
  t.sender = t.listener = options_.robot;
  t.data = data;
  t.arrival = std::numeric_limits<double>::quiet_NaN();
  std::lock_guard<std::mutex> lock(mutex_);
  ranger_.Add(t);
  Share(ToMsg(t));
}

void RangingRos::OwnTiming(const std::vector<std::uint8_t>& data, double arrival, std::uint32_t epoch, const ros::Time& stamp) {
  if (!std::isfinite(arrival)) return;  // its microphone did not hear it: nothing to share
  ranging::Timing t;
  t.stamp = stamp.toSec();
  t.sender = t.listener = options_.robot;
  t.data = data;
  t.arrival = arrival;
  t.clock_epoch = epoch;
  std::lock_guard<std::mutex> lock(mutex_);
  ranger_.Add(t);
  Share(ToMsg(t));
}

RangingRos::Known RangingRos::Heard(const std::vector<std::uint8_t>& data, double arrival, double rate_error, double direction,
                                    double direction_confidence, std::uint32_t epoch, double now, const ros::Time& stamp) {
  std::lock_guard<std::mutex> lock(mutex_);
  now_ = now;
  Known known;
  known.sender = ranger_.SenderOf(data);
  if (std::isfinite(arrival)) {
    ranging::Timing t;
    t.sender = known.sender.value_or("");
    t.listener = options_.robot;
    t.data = data;
    t.arrival = arrival;
    t.rate_error = rate_error;
    t.clock_epoch = epoch;
    t.stamp = stamp.toSec();
    // Who sent it is told by the sender's own reports; a reception of an unknown sender is
    // still shared (the sender knows it), but ranges nothing here yet.
    if (known.sender) ranger_.Add(t);
    if (known.sender) Share(ToMsg(t));
  }
  if (known.sender) {
    known.range = ranger_.RangeTo(*known.sender, now);
    if (std::isfinite(direction)) bearings_[*known.sender] = ranging::HeardBearing{direction, direction_confidence, now};
  }
  return known;
}

void RangingRos::SetClock(double now, double card_rate_error) {
  std::lock_guard<std::mutex> lock(mutex_);
  now_ = now;
  card_rate_error_ = card_rate_error;
  ranger_.SetOwnRateError(std::isfinite(card_rate_error) ? card_rate_error : 0.0);
}

InputGuard::Verdict RangingRos::OnTiming(const multirobot_audio::PacketTiming::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (msg->listener == options_.robot) return InputGuard::Verdict::Accept();  // its own, added when made
  ++received_;
  const std::uint64_t refused = ranger_.refused().total();
  ranger_.Add(FromMsg(*msg));
  if (ranger_.refused().total() != refused) {
    return InputGuard::Verdict::Reject("refused by the ranging (an unknown robot, a clock running backwards, an impossible "
                                       "rate or a payload seen twice)");
  }
  return InputGuard::Verdict::Accept();
}

void RangingRos::PublishTeammates() {
  std::lock_guard<std::mutex> lock(mutex_);
  const multirobot_audio::Teammates msg =
      ToTeammatesMsg(ranging::ViewTeammates(ranger_.Ranges(now_), bearings_, now_), frame_id_, ros::Time::now());
  teammates_pub_.publish(msg);
  if (markers_pub_.getNumSubscribers() > 0) markers_pub_.publish(ToTeammateMarkers({{options_.robot, msg}}));
}

namespace {
std::string FormatPpm(double rate_error) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f ppm", rate_error * 1e6);
  return text;
}
}  // namespace

std::string RangingRos::Summary() {
  std::lock_guard<std::mutex> lock(mutex_);
  const ranging::Refused& r = ranger_.refused();
  return "ranging: timings shared " + std::to_string(shared_) + ", received " + std::to_string(received_) + ", refused " +
         std::to_string(r.total()) + " (unknown robot " + std::to_string(r.unknown_robot) + ", backwards " +
         std::to_string(r.backwards) + ", bad rate " + std::to_string(r.bad_rate) + ", repeated payload " +
         std::to_string(r.repeated_payload) + ", implausible " + std::to_string(r.implausible) + "), teammates ranged " +
         std::to_string(ranger_.Ranges(now_).size()) + ", sound card rate " +
         (std::isfinite(card_rate_error_) ? FormatPpm(card_rate_error_) : std::string("not yet known"));
}

}  // namespace multirobot_audio
