#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/FiducialArray.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include "input_guard.h"
#include "lockstep_participant.h"
#include "sounds_good_explorer/explorer.h"

namespace multirobot_audio {

// Options of the sounds_good_explorer node, filled from its private parameters.
struct SoundsGoodExplorerNodeOptions {
  sounds_good_explorer::ExplorerOptions explorer;
  double control_rate = 10.0;  // ~control_rate: Hz of simulated time between Explorer updates
  double map_rate = 2.0;       // ~map_rate: Hz of ~local_map (0: never)
};

// Throws ParamError naming the parameter for a mistyped or out-of-range value or an unknown
// ~mode, and for options the explorer cannot work with (sounds_good_explorer::ValidateOptions
// names the field). `default_seed` is used when ~seed is unset.
SoundsGoodExplorerNodeOptions ReadSoundsGoodExplorerNodeOptions(const ros::NodeHandle& pnh,
                                                                std::uint32_t default_seed);

// One Sounds Good robot (thesis chapter 3) around the ROS-free sounds_good_explorer::Explorer.
// Runs in the robot's namespace on standard robot topics (odom, scan, fiducials, cmd_vel) and
// the robot's audio link (audio/tx, audio/rx), so it runs the same over world_sim and
// audio_propagation as on a robot with nava_modem. Finished jobs go out on `jobs`; the local
// map, plan and goal go out on ~local_map, ~plan and ~frontier for rviz. The frames are those
// of the odometry it receives (its frame_id is the odom frame, its child the base frame), so
// they match what the robot's driver broadcasts on TF.
class SoundsGoodExplorerRos {
 public:
  SoundsGoodExplorerRos(ros::NodeHandle nh, ros::NodeHandle pnh,
                        const SoundsGoodExplorerNodeOptions& options);
  ~SoundsGoodExplorerRos();

 private:
  void OnOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void OnScan(const sensor_msgs::LaserScan::ConstPtr& msg);
  void OnFiducials(const multirobot_audio::FiducialArray::ConstPtr& msg);
  void OnRx(const multirobot_audio::AudioReception::ConstPtr& msg);
  void OnControl(const ros::TimerEvent&);
  void PublishLocalMap(const ros::TimerEvent&);
  void PublishFrontier(const ros::Time& now);

  ros::NodeHandle nh_, pnh_;
  LockstepParticipant lockstep_;  // before what it hands messages and timers to
  InputGuard guard_;              // before the subscriptions whose callbacks it checks
  SoundsGoodExplorerNodeOptions options_;
  sounds_good_explorer::Explorer explorer_;
  ros::Subscriber odom_sub_, scan_sub_, fiducials_sub_, rx_sub_;
  CountedPublisher cmd_pub_, tx_pub_, jobs_pub_;
  ros::Publisher map_pub_, plan_pub_, frontier_pub_;  // for rviz only
  ros::Timer control_timer_, map_timer_;
  std::string odom_frame_, base_frame_;  // empty until the first odometry
  std::uint64_t jobs_ = 0, sent_ = 0, heard_ = 0;
  std::uint64_t updates_ = 0, late_ = 0;  // control updates, and those well behind schedule
  bool frontier_shown_ = false;  // a goal sphere is up in rviz and must be deleted when it goes
};

}  // namespace multirobot_audio
