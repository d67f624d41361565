#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace behaviours {

struct WanderOptions {
  double cruise_speed = 0.25;     // m/s in open space
  double turn_rate = 1.5;         // rad/s when turning away from an obstacle
  double avoid_range = 0.45;      // m from the centre: closer than this ahead, turn away
  double slow_range = 1.0;        // m: slow down linearly below this
  double heading_change = 0.4;    // rad/s: largest random turn while cruising
  double heading_period = 2.0;    // s between random turn changes
};

// Throws std::invalid_argument naming the field and its value: cruise_speed, turn_rate,
// avoid_range and heading_change at least 0, slow_range above avoid_range (the speed ramps
// between them), heading_period above 0.
void ValidateOptions(const WanderOptions& options);

struct VelocityCommand {
  double v = 0.0;
  double w = 0.0;
};

// Reference wandering behaviour for simulated teams: cruise with gentle random turns, and when
// a ranger ahead reads closer than avoid_range, stop and turn towards the more open side until
// the way ahead clears. Works from any evenly spread ring of range readings (ranger 0 ahead,
// counter-clockwise), +inf or NaN meaning nothing in reach. Deterministic for a seed.
class Wanderer {
 public:
  Wanderer(const WanderOptions& options, std::uint32_t seed);  // throws as ValidateOptions

  VelocityCommand Update(const std::vector<float>& ranges, double dt);

 private:
  WanderOptions options_;
  std::mt19937 rng_;
  double cruise_turn_ = 0.0;
  double until_change_ = 0.0;
  int avoid_direction_ = 0;  // +1 left, -1 right, 0 not avoiding
};

}  // namespace behaviours
