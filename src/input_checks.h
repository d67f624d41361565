#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include <geometry_msgs/Twist.h>
#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/FiducialArray.h>
#include <multirobot_audio/Job.h>
#include <multirobot_audio/LockState.h>
#include <multirobot_audio/RobotCommands.h>
#include <multirobot_audio/RobotPoses.h>
#include <multirobot_audio/RobotScans.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/LaserScan.h>

// What is wrong with a message a node received: empty when nothing is, else the first problem
// found, naming the field and its value ("pose.pose.position.x = nan"). The checks an
// InputGuard runs before a node sees a message (input_guard.h); the stamp order is the
// guard's. They turn down what no working peer sends, and nothing a working peer may send.
namespace multirobot_audio {

// Every number finite (a robot's driver reads all six).
std::string TwistProblem(const geometry_msgs::Twist& msg);
// A finite position, a finite orientation of unit length (to 1 %), a finite twist.
std::string OdometryProblem(const nav_msgs::Odometry& msg);
std::string RobotPosesProblem(const multirobot_audio::RobotPoses& msg);
// Finite angles and range limits, range_max > 0, as many ranges as angle_min..angle_max at
// angle_increment gives (to one either way), and no range negative: NaN and +-inf are readings
// (REP 117: nothing in reach, too close).
std::string ScanProblem(const sensor_msgs::LaserScan& msg);
// One scan per name, no name twice, every scan as ScanProblem wants it.
std::string RobotScansProblem(const multirobot_audio::RobotScans& msg);
// One command per name, no name twice, each one of the world's robots (`is_robot`) and as
// TwistProblem wants it.
std::string RobotCommandsProblem(const multirobot_audio::RobotCommands& msg,
                                 const std::function<bool(const std::string&)>& is_robot);
// Each marker at a finite, non-negative range and a finite bearing.
std::string FiducialsProblem(const multirobot_audio::FiducialArray& msg);
// A level (percentage, or charge / capacity) that is finite and not negative.
std::string BatteryProblem(const sensor_msgs::BatteryState& msg);
// A known kind and noise class, a finite level, a direction that is finite or NaN (unknown), a
// confidence in [0, 1], a finite quality and a path length that is NaN (unknown) or finite and
// not negative.
std::string ReceptionProblem(const multirobot_audio::AudioReception& msg);
// One of the LockState constants, a finite time in state.
std::string LockStateProblem(const multirobot_audio::LockState& msg);
// From `min_bytes` to `max_bytes` of payload (the frames the link carries; one size for a link
// of fixed packets).
std::string PacketProblem(const multirobot_audio::AudioPacket& msg, std::size_t min_bytes, std::size_t max_bytes);
// A job count of at least 1 (the first job is 1).
std::string JobProblem(const multirobot_audio::Job& msg);

}  // namespace multirobot_audio
