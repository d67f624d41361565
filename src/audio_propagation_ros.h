#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <multirobot_audio/AudioPacket.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <multirobot_audio/RobotPoses.h>

#include "audio_propagation/channel_factory.h"
#include "input_guard.h"
#include "lockstep_participant.h"
#include "simulated_ranging_ros.h"

namespace multirobot_audio {

// Options of the audio_propagation node, filled from its private parameters.
struct AudioPropagationOptions {
  // The channel served (audio_propagation/channel_factory.h), each option from the ~parameter of
  // its name (~world and ~map for world_file and map_file): ~world, ~map, ~robots, ~microphones,
  // ~profile, ~bit_rate, ~channel_model, ~decode_table, ~delivery_map_robot, ~source_level_db,
  // ~threshold_db, ~max_range, ~speed_of_sound, ~rule, ~capture_margin_db, ~direction_noise,
  // ~seed, ~cache_size, ~link_fate, ~fate_distance; ~directions (exact or measured: the
  // measured_directions flag) and ~direction_table.
  audio_propagation::SimulatedChannelOptions channel;
  // ~frame_id: the world's fixed frame: the robots' poses are looked up in it, and the paths,
  // corners and delivery maps are drawn in it.
  std::string frame_id = "map";
  double map_timeout = 30.0;     // ~map_timeout: wall seconds to wait for /map (with neither ~world nor ~map)
  double update_rate = 100.0;    // ~update_rate: Hz (simulated) of pose reads and channel steps
  // ~update: events (the channel is worked out only while something is in the air or about to
  // be: in lockstep the world does not wait for this node through silences) or every_step (at
  // every update, as before; the same run for the same seed, only slower).
  bool every_step = false;
  double carrier_refresh = 1.0;  // ~carrier_refresh: s (simulated) between repeats of an unchanged carrier
  // ~path_display_time: s (simulated) each sound path stays drawn, at least; 0 = the
  // transmission's own length (a 4-byte packet is about 0.4 s: a flicker in a sped-up run)
  double path_display_time = 0.0;
  // ~robot_poses: in lockstep, world_sim's topic of every robot's true pose
  std::string robot_poses = "/world_sim/robot_poses";
  // With ~delivery_map_robot (acoustic model): publish ~delivery_map (nav_msgs/OccupancyGrid,
  // 0-100 = percent chance a listener there decodes that robot) every ~delivery_map_period s
  // (simulated) on cells of ~delivery_map_resolution m.
  double delivery_map_period = 5.0;
  double delivery_map_resolution = 0.5;
  // ~ranging, ~arrival_errors, ~clock_rate_error, ~teammates_rate, ~ranging_window,
  // ~ranging_samples, ~ranging_offset: what receptions and audio/teammates say of distances.
  SimRangingOptions ranging;
};

// Reads the node's parameters and checks them (CheckSimulatedChannelOptions for the channel's);
// throws ParamError naming the parameter, the value and what was expected.
AudioPropagationOptions ReadAudioPropagationOptions(const ros::NodeHandle& pnh);

// Serves every simulated robot's audio link from the propagation model: audio/tx in, audio/rx
// and audio/carrier out, with the sound paths drawn for rviz.
class AudioPropagationRos {
 public:
  AudioPropagationRos(ros::NodeHandle nh, ros::NodeHandle pnh, const AudioPropagationOptions& options);
  ~AudioPropagationRos();

 private:
  InputGuard::Verdict OnTx(std::size_t robot, const multirobot_audio::AudioPacket::ConstPtr& msg);
  void OnTimer(const ros::TimerEvent& event);
  void OnRobotPoses(const multirobot_audio::RobotPoses& msg);
  // Channel time (s) of a ROS time; the first one seen starts the clock.
  double ChannelTime(const ros::Time& t);
  // In lockstep with ~update events: the ROS time (s) before which the timer has nothing to do
  // unless a packet comes (+inf: nothing until then); 0 while the air is busy.
  double RestUntil() const;
  void PublishCarriers(const ros::Time& now);
  void UpdatePoses(const ros::Time& now);
  void CheckInside(std::size_t robot, const grid::Pose2D& pose) const;
  void PublishDiffractionPoints();
  void PublishDeliveryMap(const ros::Time& now);
  // Whose pose is known, and how many look-ups failed for each robot (a robot missing from TF).
  void DiagnosePoses(diagnostic_updater::DiagnosticStatusWrapper& status);

  ros::NodeHandle nh_, pnh_;
  LockstepParticipant lockstep_;  // before what it hands messages and timers to
  diagnostic_updater::Updater updater_;
  InputGuard guard_;              // before the subscriptions whose callbacks it checks
  ros::WallTimer diagnostics_timer_;
  AudioPropagationOptions options_;
  audio_propagation::SimulatedChannel sim_;  // its robots, in the order of every per-robot vector here
  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;  // not in lockstep (poses come on ground_truth)
  std::vector<ros::Subscriber> tx_subs_;
  ros::Subscriber truth_sub_;
  std::map<std::string, std::size_t> robot_index_;
  std::vector<CountedPublisher> rx_pubs_, carrier_pubs_;
  std::unique_ptr<SimulatedRangingRos> ranging_;
  // In lockstep the poses come from world_sim's ~robot_poses (the same poses it sends on /tf),
  // counted like every other message, rather than from the TF listener's own thread; each is
  // handed to the channel with its stamp.
  std::vector<bool> last_carrier_, have_pose_;
  std::vector<double> carrier_published_;     // channel time of each robot's last carrier message
  std::vector<std::uint64_t> missing_poses_;  // per robot
  std::vector<ros::Time> pose_stamps_;        // of each robot's latest pose
  ros::Publisher paths_pub_, points_pub_, delivery_pub_, rooms_pub_;
  double next_delivery_map_ = 0.0;  // s of channel time
  ros::Timer timer_;
  ros::Time start_;
  std::uint64_t updates_ = 0, idle_updates_ = 0;
  int marker_id_ = 0;
  // Reported at shutdown.
  std::uint64_t sent_ = 0, packets_heard_ = 0, noise_heard_ = 0;
};

}  // namespace multirobot_audio
