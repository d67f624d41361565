// charging_experiment: the charging trial of thesis section 7.2 in process, no ROS. Robots
// wander on duty, look for a charger when their battery runs low, wait for the audio local
// mutex at a safe distance and dock only while they hold it.
//
//   charging_experiment [--map MAP.yaml | --world WORLD.yaml] [--robots 4] [--chargers 1]
//     [--hours 2] [--seeds 10] [--seed 1] [--out DIR] [--timeline FILE.png]
//
// Each seed draws a world (chargers and robots at random on the map; --world keeps one world
// and varies the noise) and runs it for the given hours. Writes into DIR (default
// charging_results): trials.csv (a row per seed), robots.csv (a row per robot and seed),
// worlds/seed_NNN.yaml (each world, to replay in ROS); --timeline draws the first seed's trial.
// Ends with the line
//   double_dockings D robots_flat F charges C utilisation U mean_wait_s W
// summed (D, F, C) or averaged (U over trials, W over charges) over every seed.
//
// Over machines (tool_args/shard.h): --shard K/N runs every Nth seed and writes their worlds and
// records into DIR; --merge DIR... [--out DIR] [--timeline FILE.png] makes the whole run's report
// from the shards.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "charging_demo/charging_timeline.h"
#include "charging_demo/charging_trial.h"
#include "charging_demo/charging_world.h"
#include "grid/file_path.h"
#include "grid/input_error.h"
#include "grid/map_file.h"
#include "tool_args/parallel_for.h"
#include "tool_args/progress_bar.h"
#include "tool_args/record.h"
#include "charging_experiment_args.h"
#include "tool_args/shard.h"
#include "world_sim/world_file.h"

namespace {

using namespace charging_demo;
namespace fs = std::filesystem;
using multirobot_audio::tools::BatchRun;
using tools::Protocol;

double Mean(const std::vector<double>& values) {
  if (values.empty()) return std::nan("");
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

struct Seeded {
  std::uint32_t seed = 0;
  ChargingTrialResult result;
};

void WriteCsv(const fs::path& out, const std::vector<Seeded>& runs) {
  std::ofstream trials(out / "trials.csv"), robots(out / "robots.csv");
  trials << "seed,robots,chargers,hours,charges,double_dockings,robots_flat,utilisation,mean_wait_s,"
            "give_ups,redocks,retraces,collisions,lock_packets,queue_overflows\n";
  robots << "seed,robot,charges,give_ups,redocks,retraces,wall_loops,min_battery,flat,mean_wait_s,max_wait_s,"
            "mean_seek_s\n";
  for (const Seeded& run : runs) {
    const ChargingTrialResult& r = run.result;
    std::uint64_t give_ups = 0, redocks = 0, retraces = 0;
    for (std::size_t k = 0; k < r.robots.size(); ++k) {
      const RobotRecord& robot = r.robots[k];
      give_ups += robot.give_ups;
      redocks += robot.redocks;
      retraces += robot.retraces;
      const double max_wait = robot.waits.empty() ? std::nan("")
                                                  : *std::max_element(robot.waits.begin(), robot.waits.end());
      robots << run.seed << ',' << k << ',' << robot.charges << ',' << robot.give_ups << ','
             << robot.redocks << ',' << robot.retraces << ',' << robot.wall_loops << ',' << robot.min_battery << ',' << (robot.flat ? 1 : 0) << ','
             << Mean(robot.waits) << ',' << max_wait << ',' << Mean(robot.seeks) << '\n';
    }
    trials << run.seed << ',' << r.robots.size() << ',' << r.charger_busy.size() << ','
           << r.duration / 3600.0 << ',' << r.charges() << ',' << r.double_dockings << ','
           << r.flat_robots() << ',' << r.utilisation() << ',' << r.mean_wait() << ',' << give_ups
           << ',' << redocks << ',' << retraces << ',' << r.collisions << ',' << r.packets_sent << ','
           << r.queue_overflows << '\n';
  }
  if (!trials || !robots) throw std::runtime_error((out / "trials.csv").string() + ": cannot write");
}


// One trial's result as a record (tool_args/record.h), and back. Only the first seed's record
// keeps the phases and battery samples: they are for the timeline, which draws that trial. The
// lock counters are in no report and in no record.
std::string Record(std::uint32_t seed, const ChargingTrialResult& r, bool with_timeline) {
  multirobot_audio::tools::RecordWriter w;
  w.Put(seed).Put(r.duration).Put(r.double_dockings).Put(r.collisions).Put(r.packets_sent).Put(r.queue_overflows);
  w.PutList(r.charger_busy).Put(r.robots.size());
  for (const RobotRecord& robot : r.robots) {
    w.Put(robot.charges).Put(robot.give_ups).Put(robot.redocks).Put(robot.retraces).Put(robot.wall_loops);
    w.Put(robot.flat).Put(robot.min_battery).PutList(robot.waits).PutList(robot.seeks);
    w.Put(with_timeline ? robot.phases.size() : 0);
    if (with_timeline)
      for (const PhaseSpan& span : robot.phases) w.Put(static_cast<int>(span.phase)).Put(span.start).Put(span.end);
    w.Put(with_timeline ? robot.battery.size() : 0);
    if (with_timeline)
      for (const auto& [t, level] : robot.battery) w.Put(t).Put(level);
  }
  return w.text();
}

ChargingTrialResult ReadRecord(const std::string& text, const std::string& where, std::uint32_t seed) {
  multirobot_audio::tools::RecordReader in(text, where);
  ChargingTrialResult r;
  in.Expect(seed, "seed");
  r.duration = in.Get<double>();
  r.double_dockings = in.Get<std::uint64_t>();
  r.collisions = in.Get<int>();
  r.packets_sent = in.Get<std::uint64_t>();
  r.queue_overflows = in.Get<std::uint64_t>();
  r.charger_busy = in.GetList<double>();
  r.robots.resize(in.GetCount());
  for (RobotRecord& robot : r.robots) {
    robot.charges = in.Get<std::uint64_t>();
    robot.give_ups = in.Get<std::uint64_t>();
    robot.redocks = in.Get<std::uint64_t>();
    robot.retraces = in.Get<std::uint64_t>();
    robot.wall_loops = in.Get<std::uint64_t>();
    robot.flat = in.Get<bool>();
    robot.min_battery = in.Get<double>();
    robot.waits = in.GetList<double>();
    robot.seeks = in.GetList<double>();
    robot.phases.resize(in.GetCount(3));
    for (PhaseSpan& span : robot.phases) {
      span.phase = static_cast<Phase>(in.GetInRange(0, static_cast<int>(Phase::kUndock)));
      span.start = in.Get<double>();
      span.end = in.Get<double>();
    }
    robot.battery.resize(in.GetCount(2));
    for (auto& [t, level] : robot.battery) {
      t = in.Get<double>();
      level = in.Get<double>();
    }
  }
  in.End();
  return r;
}

// The report, the same for a whole run and a merge of shards: it is made from records read back.
void Report(const Protocol& p, const std::vector<std::string>& records,
            const std::function<std::string(std::size_t)>& where) {
  std::vector<Seeded> runs(records.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    runs[i].seed = p.first_seed + static_cast<std::uint32_t>(i);
    runs[i].result = ReadRecord(records[i], where(i), runs[i].seed);
  }
  const fs::path out(p.out_dir);
  fs::create_directories(out);
  WriteCsv(out, runs);
  const ChargingTrialResult& first = runs[0].result;
  if (!p.timeline.empty())
    WriteChargingTimeline(p.timeline, first, p.options.controller.charging.low_battery,
                          "charging trial, seed " + std::to_string(runs[0].seed) + ": " +
                              std::to_string(first.robots.size()) + " robots, " +
                              std::to_string(first.charger_busy.size()) + " chargers");

  std::uint64_t double_dockings = 0, charges = 0;
  std::size_t flat = 0;
  double utilisation = 0.0, wait_sum = 0.0;
  std::size_t waits = 0;
  for (const Seeded& run : runs) {
    double_dockings += run.result.double_dockings;
    charges += run.result.charges();
    flat += run.result.flat_robots();
    utilisation += run.result.utilisation() / runs.size();
    for (const RobotRecord& r : run.result.robots)
      for (double w : r.waits) wait_sum += w, ++waits;
  }
  std::printf("trials %zu\n", runs.size());
  std::printf("double_dockings %llu robots_flat %zu charges %llu utilisation %.3f mean_wait_s %.1f\n",
              static_cast<unsigned long long>(double_dockings), flat,
              static_cast<unsigned long long>(charges), utilisation, waits ? wait_sum / waits : std::nan(""));
}

// A whole run, or one shard of it.
int Run(const Protocol& p, const BatchRun& batch) {
  const std::vector<std::size_t> which = batch.Trials(p.seeds);
  std::vector<world_sim::WorldConfig> worlds(p.seeds);
  grid::OccupancyMap map;
  if (!p.world_file.empty()) {
    world_sim::LoadedWorld loaded = world_sim::LoadWorldFile(p.world_file);
    ValidateChargingWorld(p.world_file, loaded.config);
    map = std::move(loaded.map);
    for (std::size_t s : which) worlds[s] = loaded.config;
  } else {
    const std::string canonical = grid::CanonicalPath(p.map_file);
    map = grid::LoadMapFile(canonical);
    for (std::size_t s : which) {
      std::mt19937 rng(p.first_seed + static_cast<std::uint32_t>(s));
      worlds[s] = RandomChargingWorld(map, canonical, world_sim::RobotModel{}, p.placement, rng);
    }
  }
  audio_propagation::PropagationOptions audio;
  audio.max_range = p.hearing;
  ChargingTrialOptions options = p.options;
  if (p.channel.acoustic() && !which.empty()) {
    std::vector<world_sim::WorldConfig> run;
    for (std::size_t s : which) run.push_back(worlds[s]);
    audio_propagation::tools::GiveAcoustics(p.channel, run, std::vector<std::string>(run.size(), p.world_file), map,
                                            run[0].map_file);
    for (std::size_t k = 0; k < which.size(); ++k) worlds[which[k]] = run[k];
    options.decode_table = audio_propagation::tools::LoadExperimentTable(p.channel);
    options.channel.direction_errors = audio_propagation::tools::LoadExperimentDirections(p.channel);
    audio_propagation::tools::UseAcousticPropagation(audio, run, p.hearing_given);
  }
  const fs::path out(p.out_dir);
  fs::create_directories(out / "worlds");
  for (std::size_t s : which) {
    worlds[s].seed = p.first_seed + static_cast<std::uint32_t>(s);
    char name[32];
    std::snprintf(name, sizeof name, "seed_%03u.yaml", worlds[s].seed);
    world_sim::SaveWorldFile((out / "worlds" / name).string(), worlds[s]);
  }

  const audio_propagation::PropagationModel model(map, audio);
  if (!which.empty()) {
    std::fprintf(stderr, "charging_experiment: %d seeds x %.2f h, %zu robots, %zu chargers%s\n", p.seeds, p.hours,
                 worlds[which[0]].robots.size(), worlds[which[0]].chargers.size(),
                 batch.sharded() ? (", shard " + batch.shard().Name()).c_str() : "");
  }
  multirobot_audio::tools::ProgressBar bar("trials");
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> records(p.seeds);
  multirobot_audio::tools::ParallelFor(
      which.size(), p.threads,
      [&](std::size_t k) {
        const std::size_t s = which[k];
        ChargingTrialOptions o = options;
        o.seed = worlds[s].seed;
        records[s] = Record(o.seed, RunChargingTrial(map, worlds[s], model, o), s == 0);
      },
      bar);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (batch.sharded()) {
    batch.WriteShard(p.out_dir, records);
  } else {
    Report(p, records, [](std::size_t i) { return "trial " + std::to_string(i); });
  }
  std::fprintf(stderr, "charging_experiment: %zu trials in %.1f s, written to %s\n", which.size(), wall,
               p.out_dir.c_str());
  return 0;
}

int Merge(const BatchRun& batch) {
  const multirobot_audio::tools::MergedShards shards = batch.Merge();
  const Protocol p = tools::ParseProtocol(batch.MergedArgs(shards), batch);
  const std::vector<std::string>& records = shards.Records(p.seeds);
  shards.CopyFiles(p.out_dir);
  Report(p, records, [&](std::size_t i) { return shards.Where(i); });
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool([&] {
    const tools::ExperimentCommand command = tools::ParseExperimentArgs(multirobot_audio::tools::Words(argc, argv));
    try {
      return command.batch.merging() ? Merge(command.batch) : Run(*command.run, command.batch);
    } catch (const std::exception& e) {
      std::cerr << "charging_experiment: " << e.what() << "\n";
    }
    return 1;
  });
}
