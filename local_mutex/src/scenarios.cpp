#include "local_mutex/scenarios.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>

namespace local_mutex {

grid::OccupancyMap OpenFloorMap(double size) {
  const double resolution = 0.1;
  const int cells = static_cast<int>(std::lround(size / resolution));
  return grid::OccupancyMap(cells, cells, resolution);
}

std::unique_ptr<audio_propagation::PropagationModel> OpenFloor(double size,
                                                               const std::optional<world_sim::Acoustics>& acoustics) {
  audio_propagation::PropagationOptions options;
  options.threads = 1;
  if (acoustics) audio_propagation::UseAcousticPropagation(options, *acoustics);
  return std::make_unique<audio_propagation::PropagationModel>(OpenFloorMap(size), options);
}

std::vector<TeamRobot> SingleScenario(const Eigen::Vector2d& centre) {
  return {{11, centre, {{3.3, 0, 99.8 - 43.3}}}};
}

std::vector<TeamRobot> ThreeScenario(const Eigen::Vector2d& centre) {
  return {{11, centre + Eigen::Vector2d(-1.0, 0.0), {{1.0, 0, 20.0}}},
          {30, centre + Eigen::Vector2d(1.0, 0.0), {{1.5, 0, 20.0}}},
          {212, centre + Eigen::Vector2d(0.0, 1.5), {{32.8, 2, 20.0}}}};
}

namespace {

void RequireTrial(bool ok, const char* name, double value, const char* expected) {
  if (ok) return;
  std::ostringstream text;
  text << "trials: " << name << " = " << value << ": expected " << expected;
  throw std::invalid_argument(text.str());
}

}  // namespace

void ValidateTrialOptions(const TrialOptions& o) {
  if (o.min_robots < 1 || o.max_robots < o.min_robots || o.max_robots > 255) {
    throw std::invalid_argument("trials: robots must satisfy 1 <= min <= max <= 255, got " +
                                std::to_string(o.min_robots) + ".." + std::to_string(o.max_robots));
  }
  RequireTrial(o.radius >= 0.0, "radius", o.radius, ">= 0 m");
  RequireTrial(o.spacing >= 0.0, "spacing", o.spacing, ">= 0 m");
  RequireTrial(o.want_spread >= 0.0, "want_spread", o.want_spread, ">= 0 s");
  RequireTrial(o.hold_min >= 0.0, "hold_min", o.hold_min, ">= 0 s");
  RequireTrial(o.hold_max >= o.hold_min, "hold_max", o.hold_max, "at least hold_min");
  RequireTrial(o.cycles >= 1, "cycles", o.cycles, "at least 1");
  RequireTrial(o.liveness_bound >= 0.0, "liveness_bound", o.liveness_bound, ">= 0 s (0: derived from the timers)");
}

std::vector<TeamRobot> RandomTeam(const TrialOptions& o, const Eigen::Vector2d& centre, std::mt19937& rng) {
  ValidateTrialOptions(o);
  const int n = std::uniform_int_distribution<int>(o.min_robots, o.max_robots)(rng);
  std::uniform_real_distribution<double> u(-o.radius, o.radius), want(0.0, o.want_spread),
      hold(o.hold_min, o.hold_max);
  // Distinct ids drawn from 1..255, so the order among equal request times varies.
  std::vector<int> ids(255);
  for (int k = 0; k < 255; ++k) ids[k] = k + 1;
  std::shuffle(ids.begin(), ids.end(), rng);
  std::vector<TeamRobot> team;
  for (int k = 0; k < n; ++k) {
    TeamRobot r;
    r.id = ids[k];
    for (int attempt = 0;; ++attempt) {
      if (attempt > 10000) throw std::invalid_argument("trials: cannot place robots that far apart in that radius");
      const Eigen::Vector2d p = centre + Eigen::Vector2d(u(rng), u(rng));
      if ((p - centre).norm() > o.radius) continue;
      const bool clear = std::all_of(team.begin(), team.end(),
                                     [&](const TeamRobot& t) { return (t.position - p).norm() >= o.spacing; });
      if (!clear) continue;
      r.position = p;
      break;
    }
    double at = want(rng);
    for (int c = 0; c < o.cycles; ++c) {
      r.demands.push_back({at, 0, hold(rng)});
      at += o.want_spread;  // the next cycle's wish comes after the last, whenever that is served
    }
    team.push_back(std::move(r));
  }
  return team;
}

double LivenessBound(const TrialOptions& trials, const MutexOptions& m, int robots) {
  if (trials.liveness_bound > 0.0) return trials.liveness_bound;
  // Served one after another, each robot needs at most: the holder's time, its last
  // announcement, a request and t_grab of silence; twice that for slack.
  const double per_robot = trials.hold_max + m.lock_mean + 3.0 * m.lock_sd + m.request_mean +
                           3.0 * m.request_sd + m.grab_time;
  return 2.0 * robots * per_robot;
}

std::unique_ptr<TeamSim> RunTrial(const audio_propagation::PropagationModel& model, const TrialOptions& trials,
                                  const TeamSimOptions& options, int index) {
  ValidateTrialOptions(trials);
  const grid::OccupancyMap& map = model.map();
  const Eigen::Vector2d centre = map.CellCoordsToWorld({map.width() / 2.0, map.height() / 2.0});
  TeamSimOptions o = options;
  o.seed = options.seed + static_cast<std::uint32_t>(index);
  std::mt19937 rng(o.seed);
  std::vector<TeamRobot> team = RandomTeam(trials, centre, rng);
  const double bound = LivenessBound(trials, options.mutex, static_cast<int>(team.size()));
  auto sim = std::make_unique<TeamSim>(model, std::move(team), o);
  // Long enough for every wish to be due and waited on for the bound.
  sim->Run(trials.want_spread * trials.cycles + trials.cycles * bound);
  return sim;
}

TrialOutcome RunTrialOutcome(const audio_propagation::PropagationModel& model, const TrialOptions& trials,
                             const TeamSimOptions& options, int index) {
  const std::unique_ptr<TeamSim> trial = RunTrial(model, trials, options, index);
  const TeamSim& sim = *trial;
  TrialOutcome outcome;
  outcome.seed = options.seed + static_cast<std::uint32_t>(index);
  outcome.violations = sim.violations();
  outcome.liveness_bound = LivenessBound(trials, options.mutex, static_cast<int>(sim.size()));
  for (const Grant& g : sim.grants()) outcome.waits.push_back(g.granted - g.wanted);
  std::size_t wished = 0;
  for (std::size_t k = 0; k < sim.size(); ++k) wished += sim.robot(k).demands.size();
  outcome.unserved = wished - sim.grants().size();
  for (std::size_t k = 0; k < sim.size(); ++k) outcome.packets_sent += sim.mutex(k).counters().sent;
  outcome.corrupted = sim.corrupted();
  outcome.lost = sim.lost();
  outcome.request_copies = sim.request_copies();
  return outcome;
}

TrialSummary Summarize(const std::vector<TrialOutcome>& outcomes) {
  TrialSummary s;
  double wait_sum = 0.0;
  for (const TrialOutcome& o : outcomes) {
    ++s.trials;
    s.violations += o.violations;
    s.trials_with_violations += o.violations > 0;
    for (const double wait : o.waits) {
      ++s.grants;
      wait_sum += wait;
      s.max_wait = std::max(s.max_wait, wait);
      s.liveness_failures += wait > o.liveness_bound;
    }
    s.liveness_failures += o.unserved;
    s.packets_sent += o.packets_sent;
    s.corrupted += o.corrupted;
    s.lost += o.lost;
    s.request_copies += o.request_copies;
  }
  s.mean_wait = s.grants ? wait_sum / s.grants : 0.0;
  return s;
}

TrialSummary RunTrials(const audio_propagation::PropagationModel& model, const TrialOptions& trials,
                       const TeamSimOptions& options, int count) {
  std::vector<TrialOutcome> outcomes;
  for (int t = 0; t < count; ++t) outcomes.push_back(RunTrialOutcome(model, trials, options, t));
  return Summarize(outcomes);
}

}  // namespace local_mutex
