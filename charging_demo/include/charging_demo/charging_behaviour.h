#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include <Eigen/Core>

#include "grid/pose2d.h"
#include "local_mutex/local_mutex.h"

namespace charging_demo {

struct ChargingOptions {
  std::set<std::uint32_t> chargers;  // fiducial ids that mark chargers (all look the same)
  double low_battery = 0.3;      // below this the robot goes to charge
  double full_battery = 0.98;    // charging ends here
  double wait_distance = 1.0;    // m from the charger where the robot stops and asks for the lock
  double arrive_tolerance = 0.25;  // m: this close to the waiting ring counts as there
  double undock_distance = 1.0;  // m from the charger before the lock is released
  // Waiting robots can hem a charger in (in a corridor, on both sides): after this long backing
  // away, being undock_min_distance off the charger, or no longer docked, is enough to release
  // the lock.
  double undock_timeout = 30.0;      // s
  double undock_min_distance = 0.5;  // m
  // Policy for a lock that does not come: after waiting this long the robot withdraws its
  // request and looks for another charger, avoiding this one for `avoid_time`.
  // Long enough for a queue: each charge takes about 7 minutes, so with two robots ahead a
  // 600 s timeout gave up (and lost the place in the queue) just before its turn, and on the
  // benchmark the robots that did so ran flat. Waiting costs little battery; searching more.
  double lock_timeout = 1500.0;  // s
  double avoid_time = 300.0;     // s
  // Docking that does not end docked within this time (someone in the way, odometry off) backs
  // out to the waiting point, still holding the lock, and tries again.
  double dock_timeout = 60.0;    // s
  int max_redocks = 3;           // dock timeouts in a row before giving up as after lock_timeout
  // Navigation is local (a few metres of map), so a charger remembered far away may be out of
  // its reach round walls: an approach that has not come 0.5 m closer for this long gives up
  // on that charger as after lock_timeout, and the robot searches again.
  double approach_timeout = 90.0;  // s
  double same_charger = 1.0;     // m: sightings this close together are one charger
  // Odometry drifts, so a charger remembered long ago may not be where memory says. A
  // remembered charger the robot has been within `recheck_distance` of, with it in view
  // (ChargingInputs::in_view) but unseen for `recheck_time`, is forgotten (the camera would
  // have seen it there); if it was the one the robot was approaching, waiting at or docking at,
  // the robot lets the lock go and searches again. The charger it is charging at or leaving
  // stays in memory.
  double recheck_distance = 2.0;  // m: within camera range
  double recheck_time = 5.0;      // s
};

// Throws std::invalid_argument naming the field when an option is impossible (no charger ids,
// a threshold outside (0, 1), full below low, ...).
void ValidateOptions(const ChargingOptions& options);

// m an approach must come closer by to count as progress.
constexpr double kApproachProgress = 0.5;

enum class Phase : std::uint8_t {
  kDuty,       // normal work (explore or wander)
  kSeek,       // battery low: looking for a charger
  kApproach,   // going to the waiting point wait_distance from a charger
  kWait,       // standing still at the waiting point, lock wanted
  kDock,       // lock held: driving onto the charger
  kCharge,     // docked, charging
  kUndock,     // full: backing away from the charger, lock still held
};

const char* PhaseName(Phase phase);

// What the behaviour wants the robot to do; the caller's navigation carries it out.
struct ChargingCommand {
  enum class Motion : std::uint8_t {
    kDuty,      // whatever the normal duty does (explore, wander)
    kGoTo,      // drive to `target` (odom frame)
    kStop,      // stand still
    kBackAway,  // move away from `target` (the charger)
  };
  Motion motion = Motion::kDuty;
  Eigen::Vector2d target{0.0, 0.0};
  bool want_lock = false;  // the local mutex should be wanted (or held) now
};

struct ChargerSighting {
  std::uint32_t id = 0;
  double range = 0.0;    // m
  double bearing = 0.0;  // rad, robot frame
};

// What the robot senses at one update.
struct ChargingInputs {
  grid::Pose2D odom;          // pose in the odom frame
  double battery = 1.0;       // level, 0 to 1
  bool docked = false;        // the charger's contacts are charging the robot
  std::vector<ChargerSighting> sightings;  // every fiducial seen now (others are ignored)
  local_mutex::State lock = local_mutex::State::kReleased;
  double time = 0.0;          // s
  // The caller's navigation is getting somewhere by a way of its own (going back the way it
  // came, away from the charger for a while): the approach is making progress.
  bool making_way = false;
  // Whether the robot's camera could see a point (odom frame) from where it stands, as far as
  // the caller knows (its local map shows open space to it). A remembered charger is only
  // forgotten for going unseen while it is in view. Unset: anything within recheck_distance is.
  std::function<bool(const Eigen::Vector2d&)> in_view;
};

// The charging behaviour of thesis section 7.2 (ROS-free): duty until the battery is low; find
// any charger; stop wait_distance from it and ask for the local mutex; only when HELD drive in
// and dock; charge until full; back away to undock_distance, then release; back to duty. It
// never moves while the lock is wanted but not held (the thesis's assumption for the lock's
// safety), and never drives onto a charger without holding the lock. Chargers are remembered in
// the odom frame once seen (they do not move).
class ChargingBehaviour {
 public:
  explicit ChargingBehaviour(const ChargingOptions& options);

  ChargingCommand Update(const ChargingInputs& in);

  Phase phase() const { return phase_; }
  double phase_since() const { return phase_since_; }
  std::optional<Eigen::Vector2d> charger() const { return charger_; }  // the one in use
  double charger_seen() const { return charger_seen_; }  // s, its latest sighting
  // s, when the approach under way last came kApproachProgress closer (or made way).
  double approach_progress_time() const { return approach_improved_; }
  // Every charger remembered, odom frame (at its latest sighting).
  std::vector<Eigen::Vector2d> known_chargers() const;
  std::uint64_t charges() const { return charges_; }
  // Chargers given up on: lock timeouts, failed dockings, approaches that made no progress.
  std::uint64_t give_ups() const { return give_ups_; }
  std::uint64_t redocks() const { return redocks_; }     // dock timeouts
  std::uint64_t forgotten() const { return forgotten_; }  // remembered chargers not found again

 private:
  void Enter(Phase phase, double time);
  // The nearest remembered charger not being avoided, if any.
  std::optional<Eigen::Vector2d> ChooseCharger(const Eigen::Vector2d& robot, double time) const;
  Eigen::Vector2d WaitingPoint(const Eigen::Vector2d& robot) const;

  ChargingOptions options_;
  Phase phase_ = Phase::kDuty;
  double phase_since_ = 0.0;
  void See(const std::vector<ChargerSighting>& sightings, const grid::Pose2D& odom, double time);
  void ForgetUnseen(const ChargingInputs& in);
  // Withdraws from the charger in use and avoids it for avoid_time.
  void GiveUp(double time);

  struct Known {
    Eigen::Vector2d position;  // odom frame, at the latest sighting
    std::uint32_t id = 0;      // its marker
    double seen = 0.0;         // s, latest sighting
    double near_since = -1.0;  // s, since when the robot has been within recheck_distance (< 0: not)
    Eigen::Vector2d seen_from{0.0, 0.0};  // odom frame: where the robot was at that sighting
  };
  std::vector<Known> known_;
  struct Avoided {
    Eigen::Vector2d position;  // odom frame
    double until = 0.0;        // s
  };
  std::vector<Avoided> avoid_;
  std::optional<Eigen::Vector2d> charger_;
  double charger_seen_ = 0.0;  // s, latest sighting of the charger in use
  Eigen::Vector2d charger_seen_from_{0.0, 0.0};  // odom frame: where the robot saw it from then
  bool retry_dock_ = false;  // backing out after a dock timeout, to try again
  int redocks_in_row_ = 0;
  double approach_best_ = 0.0;      // m, closest the approach has come to the charger
  double approach_improved_ = 0.0;  // s, when it last came 0.5 m closer
  std::uint64_t charges_ = 0, give_ups_ = 0, redocks_ = 0, forgotten_ = 0;
};

}  // namespace charging_demo
