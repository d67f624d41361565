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
#include <visualization_msgs/MarkerArray.h>

#include "audio_propagation/audio_channel.h"
#include "audio_propagation/delivery_map.h"
#include "audio_propagation/room_coupling.h"
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

// What rviz draws of a world: each robot as a disc with a heading arrow and its name, each
// marker as a cube with its id, each charger as a flat green zone.
visualization_msgs::MarkerArray ToWorldMarkers(const world_sim::World& world,
                                               const std::string& frame, const ros::Time& stamp);

// What a robot heard, as its audio/rx message, from the real link (nava_modem) and from the
// simulated one (audio_propagation): the same fields with the same meaning, so a controller
// cannot tell them apart. Stamped with the end of the reception.
multirobot_audio::AudioReception ToAudioReception(const nava_modem::RxEvent& event, const std::string& frame,
                                                  const ros::Time& stamp);
multirobot_audio::AudioReception ToAudioReception(const audio_propagation::Reception& reception,
                                                  const std::string& frame, const ros::Time& stamp);

// An arrow in the receiver's frame pointing where a reception came from, for rviz: longer the
// surer the direction (0.3 m at confidence 0 to 1 m at 1), green for a packet, orange for noise;
// it fades after 3 s.
visualization_msgs::Marker ToDirectionMarker(double direction, double confidence, bool packet, const std::string& frame,
                                             const ros::Time& stamp, int id);

// The sound paths of transmissions as they start, for rviz (audio_propagation's ~paths): one
// LINE_STRIP per path heard (threshold model: audible; acoustic model: a decode chance of 1 %
// or more), 15 cm up, in the namespace of its sender's name (`robots`), with ids from
// `first_id` on, lasting the packet or `display_time` s if longer. Threshold model: red at
// `levels.source_level_db` to blue at `levels.threshold_db`; acoustic model: green (sure to be
// decoded) to red (hopeless).
visualization_msgs::MarkerArray ToSoundPathMarkers(const std::vector<audio_propagation::Transmission>& started,
                                                   const std::vector<std::string>& robots,
                                                   const audio_propagation::PropagationOptions& levels,
                                                   double display_time, const std::string& frame,
                                                   const ros::Time& stamp, int first_id);

// The corners where sound bends (world points), as one green POINTS marker (namespace
// "corners") for rviz, unstamped: it stands for as long as the map.
visualization_msgs::MarkerArray ToDiffractionPointMarkers(const std::vector<Eigen::Vector2d>& corners,
                                                          const std::string& frame);

// A building's coupled rooms (audio_propagation's ~rooms) for rviz, unstamped: each room's floor
// as a CUBE_LIST of squares at least 0.25 m across, a colour a room, 1 cm up (namespace
// "room_floors"), its name, RT60 and critical distance over its centre ("room_names"), and the
// openings between rooms as yellow spheres their width across ("openings"), so that a user
// can check the cut against the map before trusting the levels.
visualization_msgs::MarkerArray ToRoomMarkers(const audio_propagation::RoomCoupling& rooms,
                                              const grid::OccupancyMap& map, const std::string& frame);

}  // namespace multirobot_audio
