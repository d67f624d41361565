#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include "audio_propagation/audio_channel.h"
#include "audio_propagation/room_coupling.h"
#include "grid/occupancy_map.h"
#include "world_sim/world.h"

// What rviz draws of the components' state: pure functions from the ROS-free components to
// visualization_msgs markers (the message conversions are in conversions.h).
namespace multirobot_audio {

// What rviz draws of a world: each robot as a disc with a heading arrow and its name, each
// marker as a cube with its id, each charger as a flat green zone.
visualization_msgs::MarkerArray ToWorldMarkers(const world_sim::World& world,
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
