#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "charging_demo/charger_search.h"
#include "charging_demo/charging_behaviour.h"
#include "grid/pose2d.h"
#include "local_mutex/local_mutex.h"
#include "sounds_good_explorer/local_navigator.h"
#include "world_sim/wanderer.h"

namespace charging_demo {

struct ControllerOptions {
  ChargingOptions charging;
  // Driving to the waiting point, onto the charger and away from it: the explorer's local-map
  // navigation (thesis section 3.3).
  sounds_good_explorer::NavigatorOptions navigation;
  // The normal duty: random wandering.
  world_sim::WanderOptions wander;
  // The search for a charger when none is known: towards the least visited surroundings.
  SearchOptions search;
  // m: robots not docking keep this far from every charger they know, so that wandering never
  // takes them over a charger another robot holds (the waiting ring is farther out).
  double keep_out = 0.6;
  std::uint32_t seed = 1;
};

// Throws std::invalid_argument naming the field of the first impossible option.
void ValidateOptions(const ControllerOptions& options);

struct ControllerOutput {
  double v = 0.0, w = 0.0;  // velocity command
  bool want_lock = false;   // the local mutex should be requested (or kept) now
};

// One charging robot (thesis section 7.2): the ChargingBehaviour decides, this carries it out
// with its sensors. Everything is in the odometry frame, so the same controller runs on the
// simulated team and on a robot; the lock is the caller's (a LocalMutex in process, the
// local_mutex node in ROS): Update() says whether it should be wanted and is told its state.
// Range readings come as a ring, ranger 0 ahead and the rest counter-clockwise, evenly spread.
// Deterministic for a seed and the same inputs.
class ChargingController {
 public:
  explicit ChargingController(const ControllerOptions& options);

  void OnOdometry(const grid::Pose2D& odom, double time);
  void OnRanges(const std::vector<sounds_good_explorer::RangeReading>& readings, double reach,
                double time);
  void OnSightings(const std::vector<ChargerSighting>& sightings);
  void OnBattery(double level, bool docked);

  ControllerOutput Update(local_mutex::State lock, double time);

  const ChargingBehaviour& behaviour() const { return behaviour_; }
  const sounds_good_explorer::LocalNavigator& navigator() const { return nav_; }
  double battery() const { return battery_; }

 private:
  // The duty: wandering, kept off every known charger.
  sounds_good_explorer::Velocity Wander(double dt);
  // The search: goal after goal towards the least visited surroundings.
  sounds_good_explorer::Velocity Search(double time);
  sounds_good_explorer::Velocity GoTo(const Eigen::Vector2d& target, double time);
  // Reverses off the charger, facing it.
  sounds_good_explorer::Velocity BackAway(const Eigen::Vector2d& charger, double time);

  ControllerOptions options_;
  ChargingBehaviour behaviour_;
  sounds_good_explorer::LocalNavigator nav_;
  world_sim::Wanderer wanderer_;
  std::mt19937 rng_;
  std::vector<sounds_good_explorer::RangeReading> ranges_;
  std::vector<ChargerSighting> sightings_;  // since the last update
  double battery_ = 1.0;
  bool docked_ = false;
  double last_update_ = 0.0;
  bool updated_ = false;
  std::optional<Eigen::Vector2d> planned_for_;  // the target of the current plan
  ChargerSearch search_;
  std::optional<Eigen::Vector2d> search_goal_;  // odom frame
  double search_since_ = 0.0;                   // s, when the goal was chosen
  std::optional<double> search_failed_;         // rad, direction of the last goal that failed
};

}  // namespace charging_demo
