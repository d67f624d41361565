#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <multirobot_audio/PacketTiming.h>
#include <multirobot_audio/Teammates.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "input_guard.h"
#include "ranging/teammate_view.h"
#include "ranging/two_way_ranger.h"

namespace multirobot_audio {

// What the ranging messages' float fields hold when there is nothing to report.
inline constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

// Options of a robot's ranging, from the nava_modem node's private parameters.
struct RangingRosOptions {
  std::string robot;                // ~robot: this robot's name (default: its namespace)
  std::vector<std::string> team;    // ~team: every robot's name; empty: any robot's reports count
  std::string timings_topic = "/audio/timings";  // ~timings_topic: the team's shared topic
  double teammates_rate = 1.0;      // ~teammates_rate: Hz of audio/teammates
  ranging::RangerOptions ranger;    // ~speed_of_sound, ~ranging_window, ~ranging_samples, ~ranging_offset
};
RangingRosOptions ReadRangingRosOptions(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);

// The ranger's parameters, shared by nava_modem and the simulation's audio_propagation:
// ~ranging_window, ~ranging_samples, ~ranging_offset (and ~speed_of_sound with `read_speed`),
// over `defaults`; throws ParamError naming the parameter.
ranging::RangerOptions ReadRangerParams(const ros::NodeHandle& pnh, ranging::RangerOptions defaults, bool read_speed);

// audio/teammates: each teammate's range and bearing where known (NaN where not).
multirobot_audio::Teammates ToTeammatesMsg(const std::vector<ranging::TeammateView>& view, const std::string& frame_id,
                                           const ros::Time& stamp);

// Two-way acoustic ranging on a real link (ranging/two_way_ranger.h) over ROS: the robot's own
// timings go out on the team's timings topic, everyone's come in, and audio/teammates says each
// heard teammate's range and bearing. Called from the audio thread (its own sends, timings and
// receptions) and from roscpp's (the team's reports, the timer); thread-safe.
class RangingRos {
 public:
  RangingRos(ros::NodeHandle nh, const RangingRosOptions& options, InputGuard& guard, const std::string& frame_id);

  // A payload queued to send: announced to the team, so that its receptions are told whose.
  void Announce(const std::vector<std::uint8_t>& data);
  // The robot's own packet as its microphone heard it (arrival on its capture clock, NaN if not).
  // `stamp`: when it was heard, by the ROS clock.
  void OwnTiming(const std::vector<std::uint8_t>& data, double arrival, std::uint32_t epoch, const ros::Time& stamp);
  // A packet it heard: shared with the team and ranged; its sender and range where known
  // (`now` is the capture clock, for ages; `stamp` when it was heard, by the ROS clock).
  struct Known {
    std::optional<std::string> sender;
    std::optional<ranging::Range> range;
  };
  Known Heard(const std::vector<std::uint8_t>& data, double arrival, double rate_error, double direction,
              double direction_confidence, std::uint32_t epoch, double now, const ros::Time& stamp);
  // The capture clock as of the audio thread's latest tick (for audio/teammates' ages), and the
  // sound card's rate over its nominal one minus 1 (NaN while unknown: taken as 0), which
  // scales every range.
  void SetClock(double now, double card_rate_error);
  std::string Summary();  // reports in and refused, for the node's exit line

 private:
  void Share(multirobot_audio::PacketTiming msg);
  InputGuard::Verdict OnTiming(const multirobot_audio::PacketTiming::ConstPtr& msg);
  void PublishTeammates();

  RangingRosOptions options_;
  std::string frame_id_;
  std::mutex mutex_;  // guards all below
  ranging::TwoWayRanger ranger_;
  std::map<std::string, ranging::HeardBearing> bearings_;  // per teammate: its latest packet heard
  double now_ = 0.0;
  double card_rate_error_ = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t shared_ = 0, received_ = 0;
  ros::Publisher timings_pub_, teammates_pub_, markers_pub_;
  ros::Subscriber timings_sub_;
  ros::WallTimer timer_;
};

// rviz: where each robot believes its teammates are, drawn in its frame (its message's
// header.frame_id) in a namespace of its name: with range and bearing, a disc at the estimate as
// wide as twice the range's standard deviation (at least 10 cm), faint as the bearing is unsure,
// the teammate's name and range, and a faint line from the robot to it; with a range alone, a ring of that radius round the robot;
// with a bearing alone, an arrow. The first marker deletes the display's earlier ones.
visualization_msgs::MarkerArray ToTeammateMarkers(const std::vector<std::pair<std::string, multirobot_audio::Teammates>>& robots);

// A report whose numbers cannot be a timing: a NaN arrival from anyone but the sender itself,
// an infinite arrival, a non-finite rate error, no names, or a payload of fewer than `min_bytes`
// or more than `max_bytes`.
std::string PacketTimingProblem(const multirobot_audio::PacketTiming& msg, std::size_t min_bytes, std::size_t max_bytes);

}  // namespace multirobot_audio
