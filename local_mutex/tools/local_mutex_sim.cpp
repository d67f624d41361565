// local_mutex_sim: the audio local mutex on the simulated audio channel, without ROS.
//
//   local_mutex_sim --scenario single|three [--timeline out.png] [timers] [--seed S]
//   local_mutex_sim --trials N [--robots 2..6] [--noise P] [--loss Q] [trial options] [timers] [--seed S]
//                   [--timeline out.png, with --trials 1: that trial]
//   local_mutex_sim --sweep N [--robots 2..6] [--seed S]
//
// Timers (s): --grab 40 --request 15 --request-sd 2 --lock 10 --lock-sd 1.
// Trial options: --radius 3 --want-spread 60 --hold-min 5 --hold-max 20 --cycles 1 --bound 0.
//
// A scenario prints one line per grant, in grant order:
//   robot ID wanted SECONDS request (T,ID) granted SECONDS released SECONDS
// then whether the grants followed request order (exit status 3 when they did not).
// Trials end with
//   trials N violations V liveness_failures L mean_wait_s M max_wait_s X
// --sweep runs N trials per cell of two tables (corrupted packets, lost receptions) against the
// number of requests sent in one t_grab, beside the thesis's (p)^n bound.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <string>

#include "local_mutex/scenarios.h"
#include "local_mutex/timeline_plot.h"
#include "tool_args/tool_args.h"

namespace {

using namespace local_mutex;

void ParseRange(const multirobot_audio::tools::ToolArgs& args, const std::string& text, int& lo, int& hi) {
  const auto dots = text.find("..");
  try {
    if (dots == std::string::npos) {
      lo = hi = std::stoi(text);
    } else {
      lo = std::stoi(text.substr(0, dots));
      hi = std::stoi(text.substr(dots + 2));
    }
  } catch (const std::exception&) {
    args.Fail("--robots: expected a count or a range like 2..8, got " + text);
  }
  if (lo < 1 || hi < lo || hi > 64) args.Fail("--robots: expected 1 <= min <= max <= 64, got " + text);
}

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

int RunScenario(const std::string& name, const TeamSimOptions& base, const std::string& timeline) {
  auto model = OpenFloor();
  const grid::OccupancyMap& map = model->map();
  const Eigen::Vector2d centre = map.CellCoordsToWorld({map.width() / 2.0, map.height() / 2.0});
  std::vector<TeamRobot> robots;
  if (name == "single") {
    robots = SingleScenario(centre);
  } else if (name == "three") {
    robots = ThreeScenario(centre);
  } else {
    std::cerr << "local_mutex_sim: --scenario: expected single or three, got " << name << "\n";
    return 1;
  }
  TeamSimOptions options = base;
  options.record = true;
  TeamSim sim(*model, std::move(robots), options);
  sim.Run(3600.0);
  bool in_order = true;
  for (std::size_t k = 0; k < sim.grants().size(); ++k) {
    const Grant& g = sim.grants()[k];
    std::printf("robot %d wanted %.1f request (%u,%u) granted %.1f released %.1f\n", sim.robot(g.robot).id,
                g.wanted, g.request.time, g.request.robot_id, g.granted, g.released);
    if (k > 0 && !Precedes(sim.grants()[k - 1].request, g.request)) in_order = false;
  }
  const bool all = sim.Done();
  std::printf("grants follow request order: %s; every robot served: %s; violations %llu\n",
              in_order ? "yes" : "NO", all ? "yes" : "NO", static_cast<unsigned long long>(sim.violations()));
  if (!timeline.empty()) {
    DrawTimeline(sim, timeline);
    std::printf("timeline written to %s\n", timeline.c_str());
  }
  return in_order && all && sim.violations() == 0 ? 0 : 3;
}

void PrintSummary(const TrialSummary& s) {
  std::printf("trials %d violations %llu liveness_failures %llu mean_wait_s %.1f max_wait_s %.1f\n", s.trials,
              static_cast<unsigned long long>(s.violations), static_cast<unsigned long long>(s.liveness_failures),
              s.mean_wait, s.max_wait);
}

void Sweep(const TrialOptions& trials, const TeamSimOptions& base, int count) {
  auto model = OpenFloor();
  const double grab = base.mutex.grab_time;
  for (const bool lose : {false, true}) {
    std::printf("\n%s, %d trials per cell, %d..%d robots\n\n",
                lose ? "Receptions lost outright (not even a carrier)" : "Packets corrupted (heard as noise)", count,
                trials.min_robots, trials.max_robots);
    std::printf("| p | n requests | t_request s | violations / grant | p^n | liveness failures | mean wait s |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const double p : {0.0, 0.1, 0.2, 0.3, 0.5}) {
      for (int n = 1; n <= 4; ++n) {
        TeamSimOptions o = base;
        // n requests fit in one t_grab of silence: at t_request, 2 t_request, ... n t_request.
        o.mutex.request_mean = grab / (n + 0.5);
        o.mutex.request_sd = o.mutex.request_mean * 2.0 / 15.0;
        o.mutex.lock_mean = std::min(base.mutex.lock_mean, o.mutex.request_mean);
        o.mutex.lock_sd = o.mutex.lock_mean * 0.1;
        (lose ? o.loss : o.noise) = p;
        const TrialSummary s = RunTrials(*model, trials, o, count);
        std::printf("| %.1f | %d | %.1f | %.4f | %.4f | %llu | %.1f |\n", p, n, o.mutex.request_mean,
                    s.grants ? static_cast<double>(s.violations) / s.grants : 0.0, std::pow(p, n),
                    static_cast<unsigned long long>(s.liveness_failures), s.mean_wait);
        std::fflush(stdout);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const multirobot_audio::tools::ToolArgs args(
      "local_mutex_sim",
      "local_mutex_sim --scenario single|three [--timeline out.png] | --trials N [--robots 2..6] [--noise P] "
      "[--loss Q] | --sweep N; timers --grab --request --request-sd --lock --lock-sd; trials --radius "
      "--want-spread --hold-min --hold-max --cycles --bound; --seed S",
      argc, argv);
  const std::string scenario = args.String("--scenario", "");
  const std::string timeline = args.String("--timeline", "");
  const long trial_count = args.Int("--trials", 0, 0, 100000000);
  const long sweep = args.Int("--sweep", 0, 0, 100000000);
  TeamSimOptions options;
  options.seed = static_cast<std::uint32_t>(args.Int("--seed", 1, 0, 4294967295L));
  options.noise = args.Double("--noise", 0.0, 0.0, 1.0);
  options.loss = args.Double("--loss", 0.0, 0.0, 1.0);
  MutexOptions& m = options.mutex;
  m.grab_time = args.Double("--grab", m.grab_time, 1e-3, 1e6);
  m.request_mean = args.Double("--request", m.request_mean, 1e-3, 1e6);
  m.request_sd = args.Double("--request-sd", m.request_sd, 0.0, 1e6);
  m.lock_mean = args.Double("--lock", m.lock_mean, 1e-3, 1e6);
  m.lock_sd = args.Double("--lock-sd", m.lock_sd, 0.0, 1e6);
  TrialOptions trials;
  ParseRange(args, args.String("--robots", "2..6"), trials.min_robots, trials.max_robots);
  trials.radius = args.Double("--radius", trials.radius, 0.0, 9.0);
  trials.want_spread = args.Double("--want-spread", trials.want_spread, 0.0, 1e6);
  trials.hold_min = args.Double("--hold-min", trials.hold_min, 0.0, 1e6);
  trials.hold_max = args.Double("--hold-max", trials.hold_max, trials.hold_min, 1e6);
  trials.cycles = static_cast<int>(args.Int("--cycles", trials.cycles, 1, 1000));
  trials.liveness_bound = args.Double("--bound", 0.0, 0.0, 1e9);
  args.CheckAllUsed();
  if ((scenario.empty() ? 0 : 1) + (trial_count > 0) + (sweep > 0) != 1) {
    args.Fail("give exactly one of --scenario, --trials N, --sweep N");
  }
  try {
    ValidateMutexOptions(m);
    if (!scenario.empty()) return RunScenario(scenario, options, timeline);
    if (!timeline.empty() && trial_count != 1) args.Fail("--timeline goes with --scenario or --trials 1");
    if (sweep > 0) {
      Sweep(trials, options, static_cast<int>(sweep));
      return 0;
    }
    const double cpu0 = CpuSeconds();
    auto model = OpenFloor();
    if (!timeline.empty()) {
      options.record = true;
      DrawTimeline(*RunTrial(*model, trials, options, 0), timeline);
      std::printf("timeline written to %s\n", timeline.c_str());
    }
    const TrialSummary s = RunTrials(*model, trials, options, static_cast<int>(trial_count));
    std::printf("grants %llu packets_sent %llu corrupted %llu lost %llu cpu_s %.1f\n",
                static_cast<unsigned long long>(s.grants), static_cast<unsigned long long>(s.packets_sent),
                static_cast<unsigned long long>(s.corrupted), static_cast<unsigned long long>(s.lost),
                CpuSeconds() - cpu0);
    PrintSummary(s);
  } catch (const std::exception& e) {
    std::cerr << "local_mutex_sim: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
