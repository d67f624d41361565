#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <multirobot_audio/ChargingState.h>
#include <multirobot_audio/FiducialArray.h>
#include <ros/time.h>
#include <sensor_msgs/LaserScan.h>
#include <visualization_msgs/MarkerArray.h>

#include "charging_demo/charging_behaviour.h"
#include "grid/pose2d.h"
#include "local_mutex/local_mutex.h"

// Pure conversions between ROS messages and the charging robot's ROS-free pieces.
namespace multirobot_audio {

// Every fiducial in view as a sighting; the behaviour itself keeps only its charger ids.
std::vector<charging_demo::ChargerSighting> ToChargerSightings(const multirobot_audio::FiducialArray& msg);

// A LockState / AcquireLock feedback state value as the lock's state; nothing for a value
// that is not one of the LockState constants.
std::optional<local_mutex::State> FromLockStateValue(std::uint8_t value);

// The controller leaves the rangers' layout to the robot: it wants a full ring, ranger 0
// straight ahead, the others counter-clockwise at even steps (world_sim's IR ring). Empty when
// `scan` is such a ring, else what is wrong with it, for a warning.
std::string RingProblem(const sensor_msgs::LaserScan& scan);

// What the node knows beside the behaviour.
struct ChargingStatus {
  local_mutex::State lock = local_mutex::State::kReleased;
  bool want_lock = false;
  double battery = 0.0;
  bool docked = false;
  bool retracing = false;     // going back along the trail to the charger
  std::uint64_t retraces = 0;
};

// The behaviour's state at `time` (s of the robot's clock) as ~state; `odom_frame` is the
// frame its chargers are remembered in.
multirobot_audio::ChargingState ToChargingState(const charging_demo::ChargingBehaviour& behaviour,
                                                const ChargingStatus& status, double time,
                                                const std::string& odom_frame, const ros::Time& stamp);

// For rviz, all in `odom_frame`: every charger the robot remembers (a flat grey disc), the one
// it uses (a disc coloured by the lock: grey RELEASED, amber WANTED or SILENT, green HELD) with
// the ring at `wait_distance` where it waits, and just below the robot (`robot`, its odom pose;
// below as seen from above, -y) a label "<label>: <phase> <LOCK> <battery %>" in the lock's
// colour (dark grey when RELEASED). The first marker deletes the previous set.
visualization_msgs::MarkerArray ToChargerMarkers(const charging_demo::ChargingBehaviour& behaviour,
                                                 const ChargingStatus& status, double wait_distance,
                                                 const std::string& label, const grid::Pose2D& robot,
                                                 const std::string& odom_frame, const ros::Time& stamp);

}  // namespace multirobot_audio
