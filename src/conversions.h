#pragma once

#include <string>
#include <vector>

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/TransformStamped.h>
#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/FiducialArray.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/LaserScan.h>

#include "audio_propagation/audio_channel.h"
#include "audio_propagation/delivery_map.h"
#include "grid/occupancy_map.h"
#include "nava_modem/packet_receiver.h"
#include "grid/pose2d.h"
#include "world_sim/fiducial_camera.h"
#include "world_sim/world.h"

// Pure conversions between the ROS-free components and ROS messages.
namespace multirobot_audio {

geometry_msgs::Quaternion ToYawQuaternion(double yaw);
double FromQuaternionYaw(const geometry_msgs::Quaternion& q);
// A pose in the plane: x, y and the yaw of its orientation.
grid::Pose2D FromPose(const geometry_msgs::Pose& pose);

// Occupied -> 100, free -> 0, unknown -> -1; same cell order (row 0 at the origin).
nav_msgs::OccupancyGrid ToOccupancyGrid(const grid::OccupancyMap& map, const std::string& frame,
                                        const ros::Time& stamp);
grid::OccupancyMap FromOccupancyGrid(const nav_msgs::OccupancyGrid& msg);
// A delivery map as a grid of percent chances (0-100), -1 where there is no listener's place.
nav_msgs::OccupancyGrid ToOccupancyGrid(const audio_propagation::DeliveryMap& map, const std::string& frame,
                                        const ros::Time& stamp);

// A ring of IR ranges as a LaserScan in `frame` (ranges measured from the robot's centre).
sensor_msgs::LaserScan ToLaserScan(const std::vector<float>& ranges,
                                   const world_sim::RobotModel& model, const std::string& frame,
                                   const ros::Time& stamp);

// A pose and body-frame velocities as Odometry of `child` in `frame`.
nav_msgs::Odometry ToOdometry(const grid::Pose2D& pose, double v, double w,
                              const std::string& frame, const std::string& child,
                              const ros::Time& stamp);

geometry_msgs::TransformStamped ToTransform(const grid::Pose2D& pose, const std::string& parent,
                                            const std::string& child, const ros::Time& stamp);

sensor_msgs::BatteryState ToBatteryState(double level, bool docked,
                                         const world_sim::BatteryModel& model,
                                         const std::string& frame, const ros::Time& stamp);

// What a controller needs of a battery: its level (0 to 1; NaN when the message gives neither
// a percentage nor a charge and capacity) and whether a charger is feeding it (status CHARGING,
// or FULL, which world_sim reports for a full battery still docked).
struct BatteryReading {
  double level = 0.0;
  bool docked = false;
};
BatteryReading FromBatteryState(const sensor_msgs::BatteryState& msg);

multirobot_audio::FiducialArray ToFiducialArray(
    const std::vector<world_sim::FiducialSighting>& seen, const std::string& frame,
    const ros::Time& stamp);

// What a robot heard, as its audio/rx message, from the real link (nava_modem) and from the
// simulated one (audio_propagation): the same fields with the same meaning, so a controller
// cannot tell them apart. Stamped with the end of the reception.
multirobot_audio::AudioReception ToAudioReception(const nava_modem::RxEvent& event, const std::string& frame,
                                                  const ros::Time& stamp);
multirobot_audio::AudioReception ToAudioReception(const audio_propagation::Reception& reception,
                                                  const std::string& frame, const ros::Time& stamp);

}  // namespace multirobot_audio
