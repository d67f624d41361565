#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "charging_demo/charger_search.h"
#include "charging_demo/charging_behaviour.h"
#include "charging_demo/trail.h"
#include "charging_demo/wall_follower.h"
#include "grid/pose2d.h"
#include "local_mutex/local_mutex.h"
#include "local_navigation/local_navigator.h"
#include "behaviours/wanderer.h"

namespace charging_demo {

struct ControllerOptions {
  ChargingOptions charging;
  // Driving to the waiting point, onto the charger and away from it: the local-map navigation
  // of thesis section 3.3 (local_navigation/, which the Sounds Good explorer drives with too).
  local_navigation::NavigatorOptions navigation;
  // The normal duty: random wandering.
  behaviours::WanderOptions wander;
  // The search for a charger when none is known: towards the least visited surroundings.
  SearchOptions search;
  // m: robots not docking keep this far from every charger they know, so that wandering never
  // takes them over a charger another robot holds (the waiting ring is farther out).
  double keep_out = 0.6;
  // The way the robot came. An approach that has not come 0.5 m closer for `retrace_after`
  // (the local map walls it off: the charger is in the corridor, the robot in a room whose door
  // the map no longer shows) goes back along the trail to where the charger was last seen,
  // cutting across to the crumb nearest that sighting among those within `retrace_reach` that
  // the local map lets it plan to.
  TrailOptions trail;
  // A search that has not found a charger in `follow_after` s goes on by following walls
  // (left hand for odd seeds, right for even), round the room and out of its door. Back where
  // it was at least 10 s before going the same way (round a pillar, or a stretch of wall between
  // two doors), or stuck for 15 s, it switches hands and takes one search goal away first.
  WallFollowOptions wall_follow;
  double follow_after = 60.0;  // s
  double retrace_after = 15.0;  // s
  double retrace_reach = 2.5;   // m
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
  void OnRanges(const std::vector<local_navigation::RangeReading>& readings, double reach,
                double time);
  void OnSightings(const std::vector<ChargerSighting>& sightings);
  void OnBattery(double level, bool docked);

  ControllerOutput Update(local_mutex::State lock, double time);

  const ChargingBehaviour& behaviour() const { return behaviour_; }
  const local_navigation::LocalNavigator& navigator() const { return nav_; }
  bool retracing() const { return retrace_.active; }
  std::uint64_t retraces() const { return retraces_; }  // approaches that went back along the trail
  // Loops (and stalls) broken while following walls.
  std::uint64_t wall_loops() const { return loops_; }
  double battery() const { return battery_; }

 private:
  // The duty: wandering, kept off every known charger.
  local_navigation::Velocity Wander(double dt);
  // The search: goal after goal towards the least visited surroundings, then walls.
  local_navigation::Velocity Search(double time, double dt);
  local_navigation::Velocity SearchGoal(double time);
  local_navigation::Velocity GoTo(const Eigen::Vector2d& target, double time);
  // To the waiting point: directly, or back along the trail when that makes no progress.
  local_navigation::Velocity Approach(const Eigen::Vector2d& target, double time);
  // Starts going back to the charger's latest sighting; false when the trail cannot help.
  bool StartRetrace(double time);
  // Every known charger but the one in use: planned round as walls.
  std::vector<Eigen::Vector2d> OtherChargers() const;
  // Reverses off the charger, facing it.
  local_navigation::Velocity BackAway(const Eigen::Vector2d& charger, double time);

  ControllerOptions options_;
  ChargingBehaviour behaviour_;
  local_navigation::LocalNavigator nav_;
  behaviours::Wanderer wanderer_;
  std::mt19937 rng_;
  std::vector<local_navigation::RangeReading> ranges_;
  std::vector<ChargerSighting> sightings_;  // since the last update
  double battery_ = 1.0;
  bool docked_ = false;
  double last_update_ = 0.0;
  bool updated_ = false;
  std::optional<Eigen::Vector2d> planned_for_;  // the target of the current plan
  ChargerSearch search_;
  std::optional<Eigen::Vector2d> search_goal_;  // odom frame
  double search_since_ = 0.0;                   // s, when the goal was chosen
  double search_start_distance_ = 0.0;          // m from the robot to the goal then
  std::optional<double> search_failed_;         // rad, direction of the last goal that failed
  Trail trail_;
  // The approach under way: which one (its charger and start).
  std::optional<Eigen::Vector2d> approach_charger_;
  double approach_since_ = -1.0;
  struct Retrace {
    bool active = false;
    std::uint64_t mark = 0;    // the crumb laid when the charger was last seen
    std::uint64_t cursor = 0;  // the crumb being driven to; only ever goes back
    double moved_back = 0.0;   // s, when the cursor last went back
  };
  Retrace retrace_;
  std::optional<std::uint64_t> retraced_mark_;  // the last mark reached: not retraced again
  std::uint64_t retraces_ = 0;
  WallFollower follower_;
  double search_phase_since_ = -1.0;  // the seek phase the search state belongs to
  bool following_ = false, escaping_ = false;
  double follow_since_ = 0.0, loop_checked_ = 0.0;
  Eigen::Vector2d follow_progress_at_{0.0, 0.0};  // where following last got somewhere
  double follow_progress_time_ = 0.0;
  std::uint64_t loops_ = 0;
  std::uint64_t goals_chosen_ = 0;  // search goals so far
  std::uint64_t escape_goal_ = 0;   // the goal escaping an island (goals_chosen_ then)
};

}  // namespace charging_demo
