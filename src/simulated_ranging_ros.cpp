#include "simulated_ranging_ros.h"

#include <cmath>
#include <limits>

#include "audio_propagation/arrival_errors_file.h"
#include "grid/input_error.h"
#include "params.h"
#include "ranging_ros.h"

namespace multirobot_audio {
namespace {

// What a listener's receiver reports of a sender's clock (ranging/simulated_ranging.h): the
// room profile's chirps measure it to some 30 ppm; nava's bit clock is not trusted (nothing).
double RateReportStd(nava_modem::Profile profile) { return profile == nava_modem::Profile::kRoom ? 30e-6 : -1.0; }

}  // namespace

SimRangingOptions ReadSimRangingOptions(const ros::NodeHandle& pnh, double speed_of_sound) {
  SimRangingOptions o;
  const std::string mode = StringParam(pnh, "ranging", "measured");
  if (mode == "measured") {
    o.mode = SimRangingMode::kMeasured;
  } else if (mode == "exact") {
    o.mode = SimRangingMode::kExact;
  } else if (mode == "off") {
    o.mode = SimRangingMode::kOff;
  } else {
    throw ParamError(pnh.resolveName("ranging") + ": expected measured, exact or off, got '" + mode + "'");
  }
  o.arrival_errors = StringParam(pnh, "arrival_errors", o.arrival_errors);
  o.clock_rate_error = NumberParam(pnh, "clock_rate_error", o.clock_rate_error, 0.0, 0.001);
  o.teammates_rate = NumberParam(pnh, "teammates_rate", o.teammates_rate, 0.01, 100.0);
  o.ranger.speed_of_sound = speed_of_sound;
  o.ranger = ReadRangerParams(pnh, o.ranger, false);
  return o;
}

SimulatedRangingRos::SimulatedRangingRos(ros::NodeHandle nh, ros::NodeHandle pnh, LockstepParticipant& lockstep,
                                         const std::vector<std::string>& robots, const SimRangingOptions& options,
                                         nava_modem::Profile profile, std::uint32_t seed)
    : options_(options), robots_(robots), bearings_(robots.size()), exact_(robots.size()) {
  if (options_.mode == SimRangingMode::kMeasured) {
    const std::string name = nava_modem::ProfileName(profile);
    arrival_errors_ = options_.arrival_errors.empty() ? audio_propagation::ShippedArrivalErrors(name) : options_.arrival_errors;
    ranging::SimulatedRangingOptions s;
    s.ranger = options_.ranger;
    try {
      s.errors = audio_propagation::LoadArrivalErrors(arrival_errors_, name);
    } catch (const grid::InputError& e) {
      throw ParamError(std::string("~arrival_errors: ") + e.what());
    }
    s.max_clock_rate_error = options_.clock_rate_error;
    s.rate_report_std = RateReportStd(profile);
    s.seed = seed;
    ranging_ = std::make_unique<ranging::SimulatedRanging>(robots_, s);
  }
  for (const std::string& robot : robots_) {
    ros::NodeHandle rnh(nh, robot);
    pubs_.push_back(lockstep.Advertise<multirobot_audio::Teammates>(rnh, "audio/teammates", 10, true));
  }
  markers_pub_ = pnh.advertise<visualization_msgs::MarkerArray>("teammates_markers", 2);
}

void SimulatedRangingRos::Started(const audio_propagation::Transmission& t) {
  if (ranging_) ranging_->Sent(t.sender, t.data, t.start);
}

void SimulatedRangingRos::Received(const audio_propagation::Reception& rx, multirobot_audio::AudioReception& msg) {
  if (rx.kind != audio_propagation::Reception::Kind::kPacket) {
    msg.path_length = msg.path_length_std = kNan;
    return;
  }
  const std::string& sender = robots_[rx.sender];
  if (std::isfinite(rx.direction)) {
    bearings_[rx.receiver][sender] = ranging::HeardBearing{rx.direction, rx.direction_confidence, rx.time};
  }
  switch (options_.mode) {
    case SimRangingMode::kExact: {
      ranging::Range& r = exact_[rx.receiver][sender];
      r.teammate = sender;
      r.range = rx.path_length;
      r.samples = 1;
      r.age = rx.time;  // when: made an age on publishing
      return;  // the message already holds the true path
    }
    case SimRangingMode::kOff:
      msg.path_length = msg.path_length_std = kNan;
      return;
    case SimRangingMode::kMeasured:
      break;
  }
  if (ranging_->Heard(rx.receiver, rx.sender, rx.data, rx.path_length, rx.time)) {
    ++timed_;
  } else {
    ++untimed_;
  }
  const auto range = ranging_->RangeTo(rx.receiver, rx.sender, rx.time);
  msg.path_length = range ? static_cast<float>(range->range) : kNan;
  msg.path_length_std = range ? static_cast<float>(range->range_std) : kNan;
}

void SimulatedRangingRos::PublishDue(double t, const ros::Time& stamp) {
  if (t < next_publish_) return;
  next_publish_ = t + 1.0 / options_.teammates_rate;
  std::vector<std::pair<std::string, multirobot_audio::Teammates>> said;
  for (std::size_t k = 0; k < robots_.size(); ++k) {
    std::vector<ranging::Range> ranges;
    if (ranging_) {
      ranges = ranging_->Ranges(k, t);
    } else {
      for (const auto& [name, r] : exact_[k]) {
        ranges.push_back(r);
        ranges.back().age = std::max(0.0, t - r.age);
      }
    }
    const multirobot_audio::Teammates msg =
        ToTeammatesMsg(ranging::ViewTeammates(ranges, bearings_[k], t), robots_[k] + "/base_link", stamp);
    pubs_[k].publish(msg);
    said.emplace_back(robots_[k], msg);
  }
  if (markers_pub_.getNumSubscribers() > 0) markers_pub_.publish(ToTeammateMarkers(said));
}

std::string SimulatedRangingRos::Summary() const {
  if (!ranging_) return std::string("ranging ") + (options_.mode == SimRangingMode::kExact ? "exact" : "off");
  return "ranging measured: " + std::to_string(timed_) + " receptions timed, " + std::to_string(untimed_) +
         " of no known sending, " + std::to_string(ranging_->refused().total()) + " timings refused";
}

}  // namespace multirobot_audio
