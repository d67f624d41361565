// sounds_good_experiment: the Sounds Good experiment (thesis chapter 3) in process, no ROS.
//
//   sounds_good_experiment --map MAP.yaml [--out DIR] [protocol options]
//   sounds_good_experiment --worlds a.yaml,b.yaml [--out DIR] [protocol options]
//   sounds_good_experiment --quick [--map MAP.yaml] [--out DIR]
//
// Protocol (defaults are the thesis's): --configs 10 --modes none,bidirectional,omni --trials 20
//   --robots 5 --jobs 20 --work 30 --hearing 15 --ir-range 1.5 --camera-range 5 --cap 20000
//   --seed 1 --threads 0 (one per core) --chart-config 9
// Explorer: --audio-weight 3 --noise-std 0.3 --announce-period 2 --announce-window 10
//   --arrive-radius 0.6
// Channel: --channel threshold (the thesis's) or acoustic, with --profile nava|room (the robots'
//   modem: packet length and decode table), --table FILE (default: the profile's shipped table)
//   and --acoustics WORLD.yaml (a world file whose acoustics section the generated configurations
//   get; with --worlds each world's own section is used unless --acoustics is given). With the
//   acoustic model there is no hearing range unless --hearing is given: the model judges.
// --quick: a small protocol for CI (3 configurations, 6 trials, 8 jobs, all three modes, on the
//   project's office map unless --map is given).
//
// Writes into DIR (default sounds_good_results): configs/config_NN.yaml (each configuration as a
// world file, to replay in ROS), trials.csv, jobs.csv, table_3_1.md, table_3_2.md,
// figure_3_6a.png, figure_3_6b.png; prints both tables and a verdict per pair of modes.
//
// Over machines (tool_args/shard.h): --shard K/N runs every Nth trial of (config, mode, trial)
// order and writes configs/ and its trials' records into DIR; --merge DIR... --out DIR makes the
// whole run's report from the shards.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>

#include "grid/file_path.h"
#include "grid/input_error.h"
#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/decode_table.h"
#include "grid/map_file.h"
#include "nava_modem/modem_profile.h"
#include "sounds_good_explorer/configurations.h"
#include "sounds_good_explorer/experiment.h"
#include "sounds_good_explorer/experiment_report.h"
#include "tool_args/progress_bar.h"
#include "tool_args/record.h"
#include "sounds_good_experiment_args.h"
#include "tool_args/shard.h"
#include "world_sim/world_file.h"

namespace {

using namespace sounds_good_explorer;
namespace fs = std::filesystem;
using multirobot_audio::tools::BatchRun;
using tools::Protocol;

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path + ": cannot write");
}

struct Setup {
  grid::OccupancyMap map;
  std::string map_file;
  std::vector<world_sim::WorldConfig> configs;
};

// Loads the given world files; they must share one map (the audio model is built once).
Setup LoadWorlds(const std::vector<std::string>& files, const TaskOptions& task) {
  Setup setup;
  for (const std::string& file : files) {
    world_sim::LoadedWorld world = world_sim::LoadWorldFile(file);
    if (setup.configs.empty()) {
      setup.map = world.map;
      setup.map_file = world.config.map_file;
    } else if (world.config.map_file != setup.map_file) {
      throw grid::InputError(file, "map", "expected the same map as " + files.front() + " (" +
                                              setup.map_file + "), got " + world.config.map_file);
    }
    ValidateConfiguration(file, world.config, setup.map, task.source, task.sink);
    setup.configs.push_back(world.config);
  }
  return setup;
}

// The configurations (loaded or generated) and, for the acoustic channel, the decode table and
// acoustics; writes each configuration into DIR/configs.
Setup MakeSetup(Protocol& p) {
  TrialOptions& trial = p.options.trial;
  Setup setup;
  if (!p.worlds.empty()) {
    setup = LoadWorlds(p.worlds, trial.explorer.task);
  } else {
    setup.map_file = grid::CanonicalPath(p.map_file);
    setup.map = grid::LoadMapFile(setup.map_file);
    std::mt19937 rng(p.options.seed);
    for (int c = 0; c < p.configs; ++c)
      setup.configs.push_back(RandomConfiguration(setup.map, setup.map_file, p.body, p.placement, rng));
  }
  if (p.channel.acoustic()) {
    trial.decode_table = audio_propagation::tools::LoadExperimentTable(p.channel);
    trial.channel.direction_errors = audio_propagation::tools::LoadExperimentDirections(p.channel);
    audio_propagation::tools::GiveAcoustics(p.channel, setup.configs, p.worlds, setup.map, setup.map_file);
  }
  fs::create_directories(fs::path(p.out_dir) / "configs");
  for (int c = 0; c < p.configs; ++c) {
    char name[32];
    std::snprintf(name, sizeof name, "config_%02d.yaml", c + 1);
    world_sim::SaveWorldFile((fs::path(p.out_dir) / "configs" / name).string(), setup.configs[c]);
  }
  return setup;
}

// One trial's result as a record (tool_args/record.h), and back into its row.
std::string Record(const TrialRow& row) {
  const TrialResult& r = row.result;
  multirobot_audio::tools::RecordWriter w;
  w.Put(row.seed).Put(r.time).Put(r.censored).Put(r.jobs.size());
  for (const JobRecord& job : r.jobs) w.Put(job.robot).Put(job.marker).Put(job.time);
  w.Put(r.collisions).Put(r.stuck).Put(r.packets_sent).Put(r.packets_heard).Put(r.queue_overflows);
  return w.text();
}

void ReadRecord(const std::string& text, const std::string& where, TrialRow& row) {
  multirobot_audio::tools::RecordReader in(text, where);
  in.Expect(row.seed, "seed");
  TrialResult& r = row.result;
  r.time = in.Get<double>();
  r.censored = in.Get<bool>();
  r.jobs.resize(in.GetCount(3));
  for (JobRecord& job : r.jobs) {
    job.robot = in.Get<std::size_t>();
    job.marker = in.Get<std::uint32_t>();
    job.time = in.Get<double>();
  }
  r.collisions = in.Get<int>();
  r.stuck = in.Get<std::uint64_t>();
  r.packets_sent = in.Get<std::uint64_t>();
  r.packets_heard = in.Get<std::uint64_t>();
  r.queue_overflows = in.Get<std::uint64_t>();
  in.End();
}

// The report, the same for a whole run and a merge of shards: it is made from records read back.
void Report(const Protocol& p, std::vector<TrialRow>& rows, const std::vector<std::string>& records,
            const std::function<std::string(std::size_t)>& where) {
  for (std::size_t i = 0; i < rows.size(); ++i) ReadRecord(records[i], where(i), rows[i]);
  const std::vector<ListenMode>& modes = p.options.modes;
  const fs::path out(p.out_dir);
  WriteTrialsCsv((out / "trials.csv").string(), rows);
  WriteJobsCsv((out / "jobs.csv").string(), rows);
  const std::string table31 = Table31(rows, modes, p.configs);
  const std::string table32 = Table32(rows, modes, p.configs);
  WriteText((out / "table_3_1.md").string(), table31);
  WriteText((out / "table_3_2.md").string(), table32);
  WriteTeamTimeChart((out / "figure_3_6b.png").string(), rows, modes, p.configs);
  WriteJobTimeChart((out / "figure_3_6a.png").string(), rows, modes, p.chart_config, p.options.trial.jobs);
  int censored = 0;
  for (const TrialRow& r : rows) censored += r.result.censored;
  std::printf("Table 3.1: time (s) for the team to finish %d jobs\n\n%s\n", p.options.trial.jobs, table31.c_str());
  std::printf("Table 3.2: two-tailed Student's t-test per pair of modes\n\n%s\n", table32.c_str());
  std::printf("%s", Verdict(rows, modes, p.configs).c_str());
  std::printf("trials %zu censored %d\n", rows.size(), censored);
}

// A whole run, or one shard of it.
int Run(Protocol p, const BatchRun& batch) {
  const Setup setup = MakeSetup(p);
  audio_propagation::PropagationOptions audio;
  audio.max_range = p.hearing;
  if (p.channel.acoustic()) audio_propagation::tools::UseAcousticPropagation(audio, setup.configs, p.hearing_given);
  const audio_propagation::PropagationModel model(setup.map, audio);
  std::vector<TrialRow> rows = ExperimentRows(p.configs, p.options);
  const std::vector<std::size_t> which = batch.Trials(rows.size());
  std::fprintf(stderr, "sounds_good_experiment: %d configurations x %zu modes x %d trials on %s%s%s\n",
               p.configs, p.options.modes.size(), p.options.trials, setup.map_file.c_str(),
               p.options.trial.channel.direction_errors ? ", directions measured" : "",
               batch.sharded() ? (", shard " + batch.shard().Name()).c_str() : "");
  multirobot_audio::tools::ProgressBar bar;
  const auto start = std::chrono::steady_clock::now();
  RunRows(setup.map, setup.configs, model, p.options, which, rows, bar);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<std::string> records(rows.size());
  for (std::size_t i : which) records[i] = Record(rows[i]);
  if (batch.sharded()) {
    batch.WriteShard(p.out_dir, records);
  } else {
    Report(p, rows, records, [](std::size_t i) { return "trial " + std::to_string(i); });
  }
  std::fprintf(stderr, "sounds_good_experiment: %zu trials in %.1f s, written to %s\n", which.size(), wall,
               p.out_dir.c_str());
  return 0;
}

int Merge(const BatchRun& batch) {
  const multirobot_audio::tools::MergedShards shards = batch.Merge();
  const Protocol p = tools::ParseProtocol(batch.MergedArgs(shards));
  std::vector<TrialRow> rows = ExperimentRows(p.configs, p.options);
  const std::vector<std::string>& records = shards.Records(rows.size());
  shards.CopyFiles(p.out_dir);
  Report(p, rows, records, [&](std::size_t i) { return shards.Where(i); });
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool([&] {
    const tools::ExperimentCommand command = tools::ParseExperimentArgs(multirobot_audio::tools::Words(argc, argv));
    try {
      return command.batch.merging() ? Merge(command.batch) : Run(*command.run, command.batch);
    } catch (const grid::InputError& e) {
      std::cerr << "sounds_good_experiment: " << e.what() << "\n";
    } catch (const std::exception& e) {
      std::cerr << "sounds_good_experiment: " << e.what() << "\n";
    }
    return 1;
  });
}
