#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <multirobot_audio/AudioReception.h>
#include <ros/ros.h>

#include "audio_propagation/audio_channel.h"
#include "audio_propagation/channel_factory.h"
#include "lockstep_participant.h"
#include "ranging/simulated_ranging.h"
#include "ranging/teammate_view.h"

namespace multirobot_audio {

// What the simulation says of distances between robots (audio_propagation's ~ranging).
enum class SimRangingMode {
  kMeasured,  // the team's two-way ranging as real robots do it (ranging/simulated_ranging.h)
  kExact,     // each reception's true path length, standard deviation 0
  kOff,       // none: NaN, as nava_modem with ~ranging false
};

struct SimRangingOptions {
  SimRangingMode mode = SimRangingMode::kMeasured;  // ~ranging: measured, exact or off
  std::string arrival_errors;       // ~arrival_errors: the table ("" for the profile's shipped one)
  double clock_rate_error = 100e-6;  // ~clock_rate_error: each sound card within +- this of true time
  double teammates_rate = 1.0;      // ~teammates_rate: Hz (simulated) of each robot's audio/teammates
  ranging::RangerOptions ranger;    // ~ranging_window, ~ranging_samples, ~ranging_offset
};

// Reads them (the speed of sound is the channel's); throws ParamError naming the parameter.
SimRangingOptions ReadSimRangingOptions(const ros::NodeHandle& pnh, double speed_of_sound);

// The simulated team's ranging over ROS: every reception's path_length and path_length_std, and
// each robot's audio/teammates, with the availability and the errors of the real link's
// (nava_modem's RangingRos); or, by mode, the exact path or nothing.
class SimulatedRangingRos {
 public:
  // `robots` in the channel's order; their audio/teammates are advertised through `lockstep`,
  // the markers on `pnh`'s ~teammates_markers.
  SimulatedRangingRos(ros::NodeHandle nh, ros::NodeHandle pnh, LockstepParticipant& lockstep, const std::vector<std::string>& robots,
                      const SimRangingOptions& options, nava_modem::Profile profile, std::uint32_t seed);

  // A transmission starting (its sender's microphone times it).
  void Started(const audio_propagation::Transmission& t);
  // A reception: timed, and its message given the receiver's range to the sender.
  void Received(const audio_propagation::Reception& rx, multirobot_audio::AudioReception& msg);
  // Each robot's audio/teammates when due at channel time `t` (s); `stamp` the ROS time.
  void PublishDue(double t, const ros::Time& stamp);
  double next_publish() const { return next_publish_; }  // channel s
  std::string Summary() const;  // for the node's exit line
  const std::string& arrival_errors() const { return arrival_errors_; }

 private:
  SimRangingOptions options_;
  std::vector<std::string> robots_;
  std::string arrival_errors_;  // the table read (measured mode)
  std::unique_ptr<ranging::SimulatedRanging> ranging_;  // measured mode
  // Per robot: each teammate's latest bearing, and (exact mode) its latest path length.
  std::vector<std::map<std::string, ranging::HeardBearing>> bearings_;
  std::vector<std::map<std::string, ranging::Range>> exact_;
  std::vector<CountedPublisher> pubs_;
  ros::Publisher markers_pub_;  // ~teammates_markers: every robot's, a namespace each
  double next_publish_ = 0.0;
  std::uint64_t timed_ = 0, untimed_ = 0;
};

}  // namespace multirobot_audio
