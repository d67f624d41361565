// local_mutex_sim: the audio local mutex on the simulated audio channel, without ROS.
//
//   local_mutex_sim --scenario single|three [--timeline out.png] [timers] [--seed S]
//   local_mutex_sim --trials N [--robots 2..6] [--noise P] [--loss Q] [trial options] [timers] [--seed S]
//                   [--timeline out.png, with --trials 1: that trial]
//   local_mutex_sim --sweep N [--robots 2..6] [--seed S]
//   local_mutex_sim --bound N [--robots 2..8] [--rho 0.001] [channel] [--seed S]
//
// Timers (s): --grab 40 --request 15 --request-sd 2 --lock 10 --lock-sd 1.
// Trial options: --radius 3 --want-spread 60 --hold-min 5 --hold-max 20 --cycles 1 --liveness-bound 0.
//
// A scenario prints one line per grant, in grant order:
//   robot ID wanted SECONDS request (T,ID) granted SECONDS released SECONDS
// then whether the grants followed request order (exit status 3 when they did not).
// Trials end with
//   trials N violations V liveness_failures L mean_wait_s M max_wait_s X
// --sweep runs N trials per cell of two tables (corrupted packets, lost receptions) against the
// number of requests sent in one t_grab, beside the thesis's (p)^n bound.
// --bound runs N trials per cell of r robots, all in earshot, and n = 1..6 requests in one
// t_grab: p_r (the share of request copies that did not reach a robot in range whole) and q_r
// (that did not reach it at all), violations per grant with a 95 % interval beside (p_r)^n and
// (q_r)^n, and the n each would choose for --rho.
//
// Over machines (tool_args/shard.h): --trials, --sweep or --bound with --shard K/N --out DIR runs
// every Nth trial (the sweep's and the bound's in cell, trial order) into DIR; --merge DIR... prints the whole
// run's report from the shards.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "local_mutex/failure_bound.h"
#include "local_mutex/scenarios.h"
#include "local_mutex/timeline_plot.h"
#include "local_mutex_sim_args.h"
#include "tool_args/record.h"
#include "tool_args/shard.h"

namespace {

using namespace local_mutex;
using multirobot_audio::tools::BatchRun;
using multirobot_audio::tools::ToolArgs;

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

int RunScenario(const std::string& name, const TeamSimOptions& base, const std::string& timeline) {
  auto model = OpenFloor(20.0, base.acoustics);
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

using Request = tools::SimRequest;

// The acoustic channel's table and acoustics (the --acoustics world's section, on the open floor:
// its noise sources and regions keep their coordinates and must lie on the floor).
void UseAcousticChannel(Request& r) {
  std::vector<world_sim::WorldConfig> world(1);
  audio_propagation::tools::GiveAcoustics(r.channel, world, {}, OpenFloorMap(), "");
  r.options.acoustics = world[0].acoustics;
  r.options.decode_table = audio_propagation::tools::LoadExperimentTable(r.channel);
  r.options.channel.direction_errors = audio_propagation::tools::LoadExperimentDirections(r.channel);
}

// The groups of trials a run is made of, each `count` trials of one TeamSimOptions and one
// TrialOptions: --trials N is one group of N, --sweep N a group of N per cell of its tables
// (tables, then rows), --bound N a group of N per (r, n) cell. Trial t of group g is trial
// g * count + t of the whole run.
struct SweepCell {
  bool lose = false;  // receptions lost (else packets corrupted)
  double p = 0.0;
  int n = 0;          // requests in one t_grab
  int robots = 0;     // --bound: the team's size, all in earshot
  TeamSimOptions options;
  TrialOptions trials;
};

constexpr int kBoundMaxRequests = 6;

std::vector<SweepCell> SweepCells(const TeamSimOptions& base, const TrialOptions& trials) {
  std::vector<SweepCell> cells;
  for (const bool lose : {false, true})
    for (const double p : {0.0, 0.1, 0.2, 0.3, 0.5})
      for (int n = 1; n <= 4; ++n) {
        TeamSimOptions o = base;
        o.mutex = WithRequestsPerGrab(base.mutex, n);
        (lose ? o.loss : o.noise) = p;
        cells.push_back({lose, p, n, 0, o, trials});
      }
  return cells;
}

std::vector<SweepCell> BoundCells(const TeamSimOptions& base, const TrialOptions& trials) {
  std::vector<SweepCell> cells;
  for (int robots = trials.min_robots; robots <= trials.max_robots; ++robots)
    for (int n = 1; n <= kBoundMaxRequests; ++n) {
      TeamSimOptions o = base;
      o.mutex = WithRequestsPerGrab(base.mutex, n);
      TrialOptions t = trials;
      t.min_robots = t.max_robots = robots;
      cells.push_back({false, base.noise, n, robots, o, t});
    }
  return cells;
}

std::vector<SweepCell> Groups(const Request& r) {
  if (r.sweep > 0) return SweepCells(r.options, r.trials);
  if (r.bound > 0) return BoundCells(r.options, r.trials);
  return {{false, 0.0, 0, 0, r.options, r.trials}};
}
int PerGroup(const Request& r) { return r.sweep > 0 ? r.sweep : r.bound > 0 ? r.bound : r.trial_count; }

// One trial's outcome as a record (tool_args/record.h), and back.
std::string Record(const TrialOutcome& o) {
  multirobot_audio::tools::RecordWriter w;
  w.Put(o.seed).Put(o.violations).Put(o.unserved).Put(o.liveness_bound).Put(o.packets_sent).Put(o.corrupted);
  w.Put(o.lost).Put(o.request_copies.offered).Put(o.request_copies.heard).Put(o.request_copies.sounded);
  w.PutList(o.waits);
  return w.text();
}

TrialOutcome ReadRecord(const std::string& text, const std::string& where, std::uint32_t seed) {
  multirobot_audio::tools::RecordReader in(text, where);
  TrialOutcome o;
  in.Expect(seed, "seed");
  o.seed = seed;
  o.violations = in.Get<std::uint64_t>();
  o.unserved = in.Get<std::uint64_t>();
  o.liveness_bound = in.Get<double>();
  o.packets_sent = in.Get<std::uint64_t>();
  o.corrupted = in.Get<std::uint64_t>();
  o.lost = in.Get<std::uint64_t>();
  o.request_copies.offered = in.Get<std::uint64_t>();
  o.request_copies.heard = in.Get<std::uint64_t>();
  o.request_copies.sounded = in.Get<std::uint64_t>();
  o.waits = in.GetList<double>();
  in.End();
  return o;
}

// The outcomes of one group's trials, as records read back.
using GroupOutcomes = std::function<std::vector<TrialOutcome>(std::size_t group)>;

// --bound's report: a row per (r, n) cell as it is done, then the n each r needs for --rho.
void ReportBound(const Request& r, const std::vector<SweepCell>& groups, const GroupOutcomes& outcomes) {
  std::printf("Failure bound: %d trials per cell, r robots all in earshot, n requests in one t_grab; p_r = request "
              "copies not decoded / offered, q_r = not heard at all (not even as noise) / offered; violations per "
              "grant with a 95 %% interval\n\n", r.bound);
  std::printf("| r | n | t_request s | p_r | (p_r)^n | q_r | (q_r)^n | violations / grant [95 %%] | grants | "
              "liveness failures | mean wait s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::pair<int, RequestCopies>> pooled;  // per team size, over its cells
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const SweepCell& cell = groups[g];
    const TrialSummary s = Summarize(outcomes(g));
    const double p = RequestLoss(s.request_copies), q = RequestSilence(s.request_copies);
    const Proportion v = WilsonInterval(std::min(s.violations, s.grants), s.grants);
    std::printf("| %d | %d | %.1f | %.4f | %.2e | %.4f | %.2e | %.2e [%.1e, %.1e] | %llu | %llu | %.1f |\n", cell.robots,
                cell.n, cell.options.mutex.request_mean, p, std::pow(p, cell.n), q, std::pow(q, cell.n), v.rate, v.low,
                v.high, static_cast<unsigned long long>(s.grants), static_cast<unsigned long long>(s.liveness_failures),
                s.mean_wait);
    if (pooled.empty() || pooled.back().first != cell.robots) pooled.push_back({cell.robots, {}});
    pooled.back().second += s.request_copies;
    std::fflush(stdout);
  }
  std::printf("\nrequests before grabbing for a failure rate under rho = %g (n = log_{p} rho, p over all n):\n", r.rho);
  const auto choose = [&](double p) {
    const int n = RequestsFor(r.rho, p);
    return n > 0 ? std::to_string(n) : std::string("none will do");
  };
  for (const auto& [robots, copies] : pooled) {
    const double p = RequestLoss(copies), q = RequestSilence(copies);
    std::printf("  r %d: p_r %.4f, q_r %.4f of %llu copies: n = %s by p_r, %s by q_r\n", robots, p, q,
                static_cast<unsigned long long>(copies.offered), choose(p).c_str(), choose(q).c_str());
  }
}

// The report of --trials, --sweep or --bound, the same for a whole run and a merge of shards. A
// whole run's sweep prints each row as its cell is done.
void Report(const Request& r, const GroupOutcomes& outcomes) {
  const std::vector<SweepCell> groups = Groups(r);
  if (r.bound > 0) {
    ReportBound(r, groups, outcomes);
    return;
  }
  if (r.sweep == 0) {
    const TrialSummary s = Summarize(outcomes(0));
    std::printf("grants %llu packets_sent %llu corrupted %llu lost %llu\n", static_cast<unsigned long long>(s.grants),
                static_cast<unsigned long long>(s.packets_sent), static_cast<unsigned long long>(s.corrupted),
                static_cast<unsigned long long>(s.lost));
    PrintSummary(s);
    return;
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const SweepCell& cell = groups[g];
    if (g == 0 || cell.lose != groups[g - 1].lose) {
      std::printf("\n%s, %d trials per cell, %d..%d robots\n\n",
                  cell.lose ? "Receptions lost outright (not even a carrier)" : "Packets corrupted (heard as noise)",
                  r.sweep, r.trials.min_robots, r.trials.max_robots);
      std::printf("| p | n requests | t_request s | violations / grant | p^n | liveness failures | mean wait s |\n");
      std::printf("|---|---|---|---|---|---|---|\n");
    }
    const TrialSummary s = Summarize(outcomes(g));
    std::printf("| %.1f | %d | %.1f | %.4f | %.4f | %llu | %.1f |\n", cell.p, cell.n, cell.options.mutex.request_mean,
                s.grants ? static_cast<double>(s.violations) / s.grants : 0.0, std::pow(cell.p, cell.n),
                static_cast<unsigned long long>(s.liveness_failures), s.mean_wait);
    std::fflush(stdout);
  }
}

// --trials or --sweep: the whole run, or one shard of it.
void RunTrialsOrSweep(const Request& r, const BatchRun& batch) {
  const double cpu0 = CpuSeconds();
  auto model = OpenFloor(20.0, r.options.acoustics);
  const std::vector<SweepCell> groups = Groups(r);
  const int count = PerGroup(r);
  if (batch.sharded()) {
    std::vector<std::string> records(groups.size() * count);
    for (std::size_t i : batch.Trials(records.size()))
      records[i] = Record(RunTrialOutcome(*model, groups[i / count].trials, groups[i / count].options, static_cast<int>(i % count)));
    batch.WriteShard(r.out, records);
  } else {
    Report(r, [&](std::size_t g) {
      std::vector<TrialOutcome> outcomes;
      for (int t = 0; t < count; ++t) {
        const TeamSimOptions& o = groups[g].options;
        const std::string record = Record(RunTrialOutcome(*model, groups[g].trials, o, t));
        outcomes.push_back(ReadRecord(record, "trial " + std::to_string(g * count + t), o.seed + t));
      }
      return outcomes;
    });
  }
  std::fprintf(stderr, "local_mutex_sim: cpu_s %.1f\n", CpuSeconds() - cpu0);
}

int Merge(const BatchRun& batch) {
  const multirobot_audio::tools::MergedShards shards = batch.Merge();
  const ToolArgs args = batch.MergedArgs(shards);
  const Request r = tools::ParseSimRequest(args, batch);
  const std::vector<SweepCell> groups = Groups(r);
  const std::size_t count = PerGroup(r);
  const std::vector<std::string>& records = shards.Records(groups.size() * count);
  Report(r, [&](std::size_t g) {
    std::vector<TrialOutcome> outcomes;
    for (std::size_t t = 0; t < count; ++t)
      outcomes.push_back(ReadRecord(records[g * count + t], shards.Where(g * count + t),
                                    groups[g].options.seed + static_cast<std::uint32_t>(t)));
    return outcomes;
  });
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool([&] {
    const tools::SimCommand command = tools::ParseSimArgs(multirobot_audio::tools::Words(argc, argv));
    const BatchRun& batch = command.batch;
    try {
      if (batch.merging()) return Merge(batch);
      Request r = *command.run;
      ValidateMutexOptions(r.options.mutex);
      if (r.channel.acoustic()) UseAcousticChannel(r);
      if (!r.scenario.empty()) return RunScenario(r.scenario, r.options, r.timeline);
      if (!r.timeline.empty() && r.trial_count != 1) batch.command().Fail("--timeline goes with --scenario or --trials 1");
      if (!r.timeline.empty()) {
        TeamSimOptions options = r.options;
        options.record = true;
        DrawTimeline(*RunTrial(*OpenFloor(20.0, options.acoustics), r.trials, options, 0), r.timeline);
        std::printf("timeline written to %s\n", r.timeline.c_str());
      }
      RunTrialsOrSweep(r, batch);
    } catch (const std::exception& e) {
      std::cerr << "local_mutex_sim: " << e.what() << "\n";
      return 1;
    }
    return 0;
  });
}
