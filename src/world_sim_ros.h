#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

#include <multirobot_audio/LockstepAck.h>
#include <multirobot_audio/LockstepHello.h>
#include <multirobot_audio/RobotCommands.h>

#include "input_guard.h"
#include "watched_publisher.h"
#include "world_sim/lockstep_coordinator.h"
#include "world_sim/world.h"

namespace multirobot_audio {

// Options of the world_sim node, filled from its private parameters.
struct WorldSimOptions {
  std::string world_file;       // ~world (required)
  std::string map_file;         // ~map: replaces the world file's map when set
  double speed = 1.0;           // ~speed: real-time factor; 0 runs as fast as possible
  double duration = 0.0;        // ~duration: simulated seconds to run, 0 = until shutdown
  double cmd_vel_timeout = 0.5; // ~cmd_vel_timeout: s of simulated time before a robot stops
  int seed = -1;                // ~seed: replaces the world file's seed when >= 0
  double markers_rate = 10.0;   // ~markers_rate: Hz of the rviz markers
  world_sim::WorldOptions world;  // ~step, ~scan_rate, ~camera_rate, ~odom_rate
  // ~lockstep: step only when every participant has answered the step (docs/simulation.md)
  bool lockstep = false;
  double lockstep_timeout = 5.0;          // ~lockstep_timeout: wall s before a silent participant is dropped
  double lockstep_start_timeout = 60.0;   // ~lockstep_start_timeout: wall s to wait for them all at the start
  // ~lockstep_start_delay: wall s to wait once they are all ready, before the first step, for
  // observers outside the lockstep (a recorder) to connect to the team's publishers
  double lockstep_start_delay = 0.0;
  std::vector<std::string> participants;  // ~lockstep_participants: node names
};

// Reads the options from `pnh`; throws ParamError on anything out of range.
WorldSimOptions ReadWorldSimOptions(const ros::NodeHandle& pnh);

// The ROS face of world_sim::World: owns /clock, publishes the map, every robot's sensors,
// ground truth and TF (and, while someone listens, ~robot_scans: every scan in one message), and
// drives the robots from their cmd_vel topics and ~robot_commands (several robots in one message).
class WorldSimRos {
 public:
  // Loads the world; throws grid::InputError or std::invalid_argument on bad input.
  WorldSimRos(ros::NodeHandle nh, ros::NodeHandle pnh, const WorldSimOptions& options);

  // Steps until shutdown or the set duration; returns the summary: a line of simulated figures
  // (the same for the same world, seed and commands) and a line of wall-clock ones.
  std::string Run();

 private:
  struct RobotIo {
    ros::Subscriber cmd_vel;
    std::string cmd_vel_topic;
    WatchedPublisher scan, odom, ground_truth, fiducials, battery;
    double last_cmd_time = -1e9;
    std::string odom_frame, base_frame;
  };

  // Lockstep: counts a command (cmd_vel, ~robot_commands) as received, whatever the guard makes of it.
  void CountReceived(const std::string& topic, const std::string& publisher);
  void OnCmdVel(std::size_t index, const geometry_msgs::Twist& msg);
  // ~robot_commands: several robots' commands in one message, each as its cmd_vel.
  void OnRobotCommands(const multirobot_audio::RobotCommands& msg);
  void Publish();
  void SetUpLockstep();
  // Lockstep: counts a message the world published on `topic`.
  void Count(const WatchedPublisher& pub);
  void OnHello(const multirobot_audio::LockstepHello::ConstPtr& msg);
  void OnAck(const multirobot_audio::LockstepAck::ConstPtr& msg);
  std::map<std::string, int> OwnConnected() const;
  void StartLockstep();          // waits until every participant is ready (or dropped)
  void RunStepWithParticipants();
  void PublishClock(const ros::Time& now); // sends the step's orders, waits for the answers

  ros::NodeHandle nh_, pnh_;
  WorldSimOptions options_;
  std::unique_ptr<world_sim::World> world_;
  std::vector<RobotIo> io_;
  ros::Publisher clock_pub_, map_pub_;
  WatchedPublisher markers_pub_, robot_poses_pub_, robot_scans_pub_, tf_pub_;
  ros::Subscriber robot_commands_sub_;
  std::string robot_commands_topic_;
  std::map<std::string, std::size_t> robot_index_;  // robot name -> io_
  InputGuard guard_;
  std::uint64_t markers_every_ = 1;
  std::uint64_t battery_every_ = 1;
  // Lockstep
  std::unique_ptr<world_sim::LockstepCoordinator> lockstep_;
  ros::Subscriber hello_sub_, ack_sub_;
  std::map<std::string, ros::Publisher> order_pubs_;
  std::set<std::string> ordered_;                    // participants that have had an order
  std::map<world_sim::StreamId, std::uint64_t> cmd_received_;
  std::uint64_t lockstep_step_ = 0;
  std::set<std::string> strangers_;  // hellos from nodes that are not participants
};

}  // namespace multirobot_audio
