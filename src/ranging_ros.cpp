#include "ranging_ros.h"

#include <cmath>
#include <limits>

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

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

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
  ranging::RangerOptions& r = o.ranger;
  r.speed_of_sound = NumberParam(pnh, "speed_of_sound", r.speed_of_sound);
  r.pair_window = NumberParam(pnh, "ranging_window", r.pair_window);
  r.samples = IntParam(pnh, "ranging_samples", r.samples);
  r.offset = NumberParam(pnh, "ranging_offset", r.offset);
  CheckOptionParams(pnh, {"speed_of_sound", "ranging_window", "ranging_samples", "ranging_offset"}, [&] {
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
  return o;
}

std::string PacketTimingProblem(const multirobot_audio::PacketTiming& m, std::size_t bytes) {
  if (m.sender.empty()) return "sender is empty";
  if (m.listener.empty()) return "listener is empty";
  if (m.data.size() != bytes) return "data has " + std::to_string(m.data.size()) + " bytes, expected " + std::to_string(bytes);
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
  timings_sub_ = guard.Subscribe<multirobot_audio::PacketTiming>(
      nh, options_.timings_topic, 200, [](const multirobot_audio::PacketTiming& m) { return PacketTimingProblem(m, 4); },
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
    if (std::isfinite(direction)) bearings_[*known.sender] = Bearing{direction, direction_confidence, now};
  }
  return known;
}

void RangingRos::SetClock(double now) {
  std::lock_guard<std::mutex> lock(mutex_);
  now_ = now;
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
  multirobot_audio::Teammates msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = frame_id_;
  std::lock_guard<std::mutex> lock(mutex_);
  std::map<std::string, multirobot_audio::Teammate> by_name;
  auto entry = [&](const std::string& name) -> multirobot_audio::Teammate& {
    auto it = by_name.find(name);
    if (it != by_name.end()) return it->second;
    multirobot_audio::Teammate t;
    t.name = name;
    t.range = t.range_std = t.range_age = t.bearing = t.bearing_age = kNan;
    return by_name.emplace(name, t).first->second;
  };
  for (const ranging::Range& r : ranger_.Ranges(now_)) {
    multirobot_audio::Teammate& t = entry(r.teammate);
    t.range = static_cast<float>(r.range);
    t.range_std = static_cast<float>(r.range_std);
    t.range_age = static_cast<float>(r.age);
    t.range_samples = static_cast<std::uint32_t>(r.samples);
  }
  for (const auto& [name, b] : bearings_) {
    multirobot_audio::Teammate& t = entry(name);
    t.bearing = static_cast<float>(b.bearing);
    t.bearing_confidence = static_cast<float>(b.confidence);
    t.bearing_age = static_cast<float>(std::max(0.0, now_ - b.at));
  }
  for (auto& [name, t] : by_name) msg.teammates.push_back(t);
  teammates_pub_.publish(msg);
}

std::string RangingRos::Summary() {
  std::lock_guard<std::mutex> lock(mutex_);
  const ranging::Refused& r = ranger_.refused();
  return "ranging: timings shared " + std::to_string(shared_) + ", received " + std::to_string(received_) + ", refused " +
         std::to_string(r.total()) + " (unknown robot " + std::to_string(r.unknown_robot) + ", backwards " +
         std::to_string(r.backwards) + ", bad rate " + std::to_string(r.bad_rate) + ", repeated payload " +
         std::to_string(r.repeated_payload) + ", implausible " + std::to_string(r.implausible) + "), teammates ranged " +
         std::to_string(ranger_.Ranges(now_).size());
}

}  // namespace multirobot_audio
