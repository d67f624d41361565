#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "grid/pose2d.h"
#include "world_sim/acoustics.h"

namespace world_sim {

enum class Microphone { kOmni, kBidirectional, kNone };

// Parses "omni", "bidirectional" or "none"; nullopt otherwise.
std::optional<Microphone> ParseMicrophone(const std::string& name);
const char* MicrophoneName(Microphone m);

// How odometry drifts from the truth: each step's true motion is scaled by (1 + n) with
// n ~ N(0, linear) for translation and N(0, angular) for rotation, and the heading also drifts by
// `heading_bias` rad per metre driven.
struct OdometryNoise {
  double linear = 0.01;
  double angular = 0.02;
  double heading_bias = 0.0;
};

// Battery levels are fractions of a full charge, 0 to 1.
struct BatteryModel {
  double idle_drain = 1.0 / 7200.0;  // per second, whatever the robot does (2 h standing)
  double motion_drain = 1.0 / 3000.0;  // per metre driven
  double charge_rate = 1.0 / 600.0;  // per second while docked (empty to full in 10 min)
  double empty_voltage = 12.0;       // V at level 0
  double full_voltage = 16.8;        // V at level 1
  double capacity_ah = 3.0;          // reported in sensor_msgs/BatteryState
};

// The robot every world uses, after the thesis's robots (15 cm disc, 0.3 m/s, eight 1.5 m IR
// rangers, a 5 m fiducial camera).
struct RobotModel {
  double radius = 0.075;
  double max_speed = 0.3;      // m/s
  double max_turn_rate = 2.0;  // rad/s
  int ir_count = 8;            // rangers spread evenly around the body, the first facing ahead
  double ir_range = 1.5;       // m beyond the body's edge
  double camera_range = 5.0;   // m
  double camera_fov = 2.0 * M_PI;  // rad, centred on the heading
  OdometryNoise odometry;
  BatteryModel battery;
};

struct RobotSpec {
  std::string name;
  grid::Pose2D start;
  Microphone microphone = Microphone::kOmni;
  double battery = 1.0;  // initial level
};

struct MarkerSpec {
  std::uint32_t id = 0;
  double x = 0.0;
  double y = 0.0;
};

// A charger: a robot whose centre comes within `radius` of `pose` is docked and charges.
// With a marker id, the charger also carries a fiducial the cameras see.
struct ChargerSpec {
  grid::Pose2D pose;
  double radius = 0.2;
  std::optional<std::uint32_t> marker;
};

// Everything a world file describes, with the map file resolved to a canonical path
// (absolute, symbolic links resolved: grid::CanonicalPath).
struct WorldConfig {
  std::string map_file;
  std::uint32_t seed = 1;
  RobotModel model;
  std::vector<RobotSpec> robots;
  std::vector<MarkerSpec> markers;
  std::vector<ChargerSpec> chargers;
  // The optional `acoustics` section: read only by the acoustic channel model.
  std::optional<Acoustics> acoustics;
};

}  // namespace world_sim
