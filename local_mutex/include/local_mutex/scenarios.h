#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "audio_propagation/propagation_model.h"
#include "local_mutex/team_sim.h"

namespace local_mutex {

// An empty floor `size` m square (0.1 m cells), its corner at the origin.
grid::OccupancyMap OpenFloorMap(double size = 20.0);
// Its propagation model, one thread, with the thesis-like default hearing model; with
// `acoustics`, as the acoustic channel model needs it (no hearing range, paths down to 30 dB
// under the ambient noise).
std::unique_ptr<audio_propagation::PropagationModel> OpenFloor(
    double size = 20.0, const std::optional<world_sim::Acoustics>& acoustics = std::nullopt);

// The thesis's Figure 7.5(a): robot 11 alone wants the lock at 3.3 s and holds it until 99.8 s.
std::vector<TeamRobot> SingleScenario(const Eigen::Vector2d& centre);
// The thesis's Figure 7.5(b) and Table 7.1: robots 11 and 30 want the lock at the start, robot
// 212 at 32.8 s once it has heard two packets; each holds it for 20 s.
std::vector<TeamRobot> ThreeScenario(const Eigen::Vector2d& centre);

struct TrialOptions {
  int min_robots = 2, max_robots = 6;  // each trial draws its team size in this range
  double radius = 3.0;                 // m: robots stand within this distance of the centre...
  double spacing = 0.5;                // m: ...and at least this far apart
  double want_spread = 60.0;           // s: each robot wants the lock at a uniform time in [0, this]
  double hold_min = 5.0, hold_max = 20.0;  // s the lock is kept
  int cycles = 1;                      // demands per robot
  // A robot that waits longer than this for the lock is a liveness failure (0: derive it from
  // the timers, as the time the whole team could take to be served one after another).
  double liveness_bound = 0.0;
};

// Throws std::invalid_argument naming the field, its value and what was expected: team sizes
// outside 1 <= min_robots <= max_robots <= 255 (the lock's ids), a negative radius, spacing,
// want_spread, hold time or liveness_bound, hold_max under hold_min, cycles under 1.
void ValidateTrialOptions(const TrialOptions& options);

// A random team for one trial; throws std::invalid_argument for impossible options.
std::vector<TeamRobot> RandomTeam(const TrialOptions& options, const Eigen::Vector2d& centre, std::mt19937& rng);

// The liveness bound actually used for `robots` robots.
double LivenessBound(const TrialOptions& trials, const MutexOptions& mutex, int robots);

struct TrialSummary {
  int trials = 0;
  std::uint64_t violations = 0;         // grants while another robot in range held the lock
  int trials_with_violations = 0;
  std::uint64_t liveness_failures = 0;  // demands not granted within the bound
  std::uint64_t grants = 0;
  double mean_wait = 0.0, max_wait = 0.0;  // s from wanting to holding
  std::uint64_t packets_sent = 0, corrupted = 0, lost = 0;
  RequestCopies request_copies;
};

// What one trial leaves for a summary: enough to sum any number of trials (a whole run's or
// those gathered from shards) exactly as they were run.
struct TrialOutcome {
  std::uint32_t seed = 0;
  std::uint64_t violations = 0;
  std::uint64_t unserved = 0;  // demands never granted: still waiting, or wished after the run's end
  double liveness_bound = 0.0; // s: a longer wait is a liveness failure
  std::uint64_t packets_sent = 0, corrupted = 0, lost = 0;
  RequestCopies request_copies;
  std::vector<double> waits;   // s from wanting to holding, per grant in grant order
};

// Trial number `index` of a series (seed options.seed + index), run to its end.
std::unique_ptr<TeamSim> RunTrial(const audio_propagation::PropagationModel& model, const TrialOptions& trials,
                                  const TeamSimOptions& options, int index);
// The same trial's outcome.
TrialOutcome RunTrialOutcome(const audio_propagation::PropagationModel& model, const TrialOptions& trials,
                             const TeamSimOptions& options, int index);

// The trials summed in order.
TrialSummary Summarize(const std::vector<TrialOutcome>& outcomes);

// Runs `trials` random trials on `model`, seeds options.seed, options.seed + 1, ...
TrialSummary RunTrials(const audio_propagation::PropagationModel& model, const TrialOptions& trials,
                       const TeamSimOptions& options, int count);

}  // namespace local_mutex
