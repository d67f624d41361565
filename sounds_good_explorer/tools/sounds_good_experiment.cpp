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
#include "tool_args/shard.h"
#include "tool_args/tool_args.h"
#include "world_sim/world_file.h"

namespace {

using namespace sounds_good_explorer;
namespace fs = std::filesystem;
using multirobot_audio::tools::BatchRun;
using multirobot_audio::tools::ToolArgs;

const char* kUsage =
    "sounds_good_experiment (--map MAP.yaml | --worlds W1.yaml,W2.yaml | --quick) [--out DIR]\n"
    "  [--configs 10] [--modes none,bidirectional,omni] [--trials 20] [--robots 5] [--jobs 20]\n"
    "  [--work 30] [--hearing 15] [--ir-range 1.5] [--camera-range 5] [--cap 20000] [--seed 1]\n"
    "  [--threads 0] [--chart-config 9] [--audio-weight 3] [--noise-std 0.3]\n"
    "  [--announce-period 2] [--announce-window 10] [--arrive-radius 0.6]\n"
    "  [--channel threshold|acoustic] [--profile nava|room] [--table FILE] [--acoustics WORLD.yaml]\n"
    "  [--shard K/N] | --merge SHARD_DIR... [--out DIR]";

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');)
    if (!part.empty()) parts.push_back(part);
  return parts;
}

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

// What the command line asks for.
struct Protocol {
  ExperimentOptions options;
  ConfigurationOptions placement;
  world_sim::RobotModel body;
  std::vector<std::string> worlds;  // world files to run, or none: configurations are generated
  std::string map_file;
  int configs = 0;                  // the number of configurations (generated or given)
  double hearing = 15.0;
  bool hearing_given = false;
  int chart_config = 9;
  std::string out_dir, channel, profile_name, table_file, acoustics_file;
};

Protocol ParseProtocol(const ToolArgs& args) {
  Protocol p;
  const bool quick = args.Switch("--quick");
  ExperimentOptions& options = p.options;
  TrialOptions& trial = options.trial;
  ExplorerOptions& explorer = trial.explorer;
  const std::string worlds = args.String("--worlds", "");
  p.map_file = args.String("--map", quick ? MULTIROBOT_AUDIO_MAPS_DIR "/office.yaml" : "");
  if (worlds.empty() && p.map_file.empty()) args.Fail("give --map, --worlds or --quick");
  if (!worlds.empty() && !args.String("--map", "").empty()) args.Fail("give --map or --worlds, not both");
  if (!worlds.empty() && Split(worlds).empty()) args.Fail("--worlds: expected world files separated by commas, got '" + worlds + "'");
  if (!worlds.empty()) {
    if (quick) args.Fail("--quick makes configurations; give --worlds without it");
    for (const char* flag : {"--configs", "--robots", "--ir-range", "--camera-range"})
      if (!args.String(flag, "").empty())
        args.Fail(std::string(flag) + " makes configurations; the world files given by --worlds are used as they are");
  }
  p.worlds = Split(worlds);

  p.configs = static_cast<int>(args.Int("--configs", quick ? 3 : 10, 1, 1000));
  if (!p.worlds.empty()) p.configs = static_cast<int>(p.worlds.size());
  options.trials = static_cast<int>(args.Int("--trials", quick ? 6 : 20, 1, 100000));
  options.modes.clear();
  for (const std::string& name : Split(args.String("--modes", "none,bidirectional,omni"))) {
    const auto mode = ParseListenMode(name);
    if (!mode) args.Fail("--modes: expected none, bidirectional or omni, got '" + name + "'");
    options.modes.push_back(*mode);
  }
  if (options.modes.empty()) args.Fail("--modes: expected at least one mode");
  p.placement.robots = static_cast<int>(args.Int("--robots", 5, 1, 200));
  trial.jobs = static_cast<int>(args.Int("--jobs", quick ? 8 : 20, 1, 100000));
  explorer.task.work_time = args.Double("--work", 30.0, 0.0, 1e6);
  p.hearing = args.Double("--hearing", 15.0, 0.0, 1e4);
  p.hearing_given = !args.String("--hearing", "").empty();
  // The thesis's robots never ran flat; world_sim's do (about two hours), which would stop long
  // "no audio" trials. Generated configurations carry no battery drain.
  p.body.battery.idle_drain = 0.0;
  p.body.battery.motion_drain = 0.0;
  p.body.ir_range = args.Double("--ir-range", 1.5, 0.01, 100.0);
  p.body.camera_range = args.Double("--camera-range", 5.0, 0.01, 1000.0);
  trial.time_cap = args.Double("--cap", 20000.0, 1.0, 1e8);
  options.seed = static_cast<std::uint32_t>(args.Int("--seed", 1, 0, 4294967295L));
  options.threads = static_cast<int>(args.Int("--threads", 0, 0, 1024));
  p.chart_config = static_cast<int>(args.Int("--chart-config", 9, 1, 1000));
  if (p.chart_config > p.configs && !args.String("--chart-config", "").empty())
    args.Fail("--chart-config: expected a configuration from 1 to " + std::to_string(p.configs) +
              ", got " + std::to_string(p.chart_config));
  p.chart_config = std::min(p.chart_config, p.configs);
  explorer.frontier.audio_weight = args.Double("--audio-weight", explorer.frontier.audio_weight, 0.0, 1e6);
  explorer.frontier.noise_std = args.Double("--noise-std", explorer.frontier.noise_std, 0.0, 1e6);
  explorer.task.announce_period = args.Double("--announce-period", explorer.task.announce_period, 0.01, 1e6);
  explorer.task.announce_window = args.Double("--announce-window", explorer.task.announce_window, 0.0, 1e6);
  explorer.task.arrive_radius = args.Double("--arrive-radius", explorer.task.arrive_radius, 0.01, 100.0);
  p.out_dir = args.String("--out", "sounds_good_results");
  p.channel = args.String("--channel", "threshold");
  if (p.channel != "threshold" && p.channel != "acoustic") args.Fail("--channel: expected threshold or acoustic, got '" + p.channel + "'");
  p.profile_name = args.String("--profile", "nava");
  const auto profile = nava_modem::ParseProfile(p.profile_name);
  if (!profile) args.Fail(std::string("--profile: expected ") + nava_modem::kProfileNames + ", got '" + p.profile_name + "'");
  nava_modem::UseProfileTiming(*profile, {}, trial.channel.mac);
  p.table_file = args.String("--table", "");
  p.acoustics_file = args.String("--acoustics", "");
  if (p.channel != "acoustic" && (!p.table_file.empty() || !p.acoustics_file.empty())) {
    args.Fail(std::string(p.table_file.empty() ? "--acoustics" : "--table") + " is for --channel acoustic");
  }
  args.CheckAllUsed();
  p.placement.source = explorer.task.source;
  p.placement.sink = explorer.task.sink;
  return p;
}

// The configurations (loaded or generated) and, for the acoustic channel, the decode table and
// acoustics; writes each configuration into DIR/configs.
Setup MakeSetup(Protocol& p) {
  TrialOptions& trial = p.options.trial;
  Setup setup;
  if (!p.worlds.empty()) {
    setup = LoadWorlds(p.worlds, trial.explorer.task);
  } else {
    setup.map_file = fs::absolute(p.map_file).lexically_normal().string();
    setup.map = grid::LoadMapFile(setup.map_file);
    std::mt19937 rng(p.options.seed);
    for (int c = 0; c < p.configs; ++c)
      setup.configs.push_back(RandomConfiguration(setup.map, setup.map_file, p.body, p.placement, rng));
  }
  if (p.channel == "acoustic") {
    trial.decode_table = std::make_shared<const audio_propagation::DecodeTable>(audio_propagation::LoadDecodeTable(
        p.table_file.empty() ? audio_propagation::ShippedDecodeTable(p.profile_name) : p.table_file, p.profile_name));
    if (!p.acoustics_file.empty()) {
      const world_sim::LoadedWorld source = world_sim::LoadWorldFile(p.acoustics_file, setup.map_file);
      if (!source.config.acoustics) throw grid::InputError(p.acoustics_file, "acoustics", "expected an acoustics section");
      for (world_sim::WorldConfig& c : setup.configs) c.acoustics = source.config.acoustics;
    }
    for (std::size_t c = 0; c < setup.configs.size(); ++c) {
      if (!setup.configs[c].acoustics) {
        throw grid::InputError(p.worlds.empty() ? "--acoustics" : p.worlds[c], "acoustics",
                               "--channel acoustic needs an acoustics section (give --acoustics WORLD.yaml)");
      }
      world_sim::ValidateWorld(p.acoustics_file.empty() ? p.worlds[c] : p.acoustics_file, setup.configs[c], setup.map);
    }
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
int Run(const ToolArgs& args, const BatchRun& batch) {
  Protocol p = ParseProtocol(args);
  const Setup setup = MakeSetup(p);
  audio_propagation::PropagationOptions audio;
  audio.max_range = p.hearing;
  if (p.options.trial.decode_table) {
    // The acoustic model judges every path: no hearing range unless one is asked for, and paths
    // down to 30 dB under the quietest world's ambient noise.
    if (!p.hearing_given) audio.max_range = 0.0;
    for (const world_sim::WorldConfig& c : setup.configs)
      audio.threshold_db = std::min(audio.threshold_db, audio_propagation::AcousticThresholdDb(*c.acoustics));
  }
  const audio_propagation::PropagationModel model(setup.map, audio);
  std::vector<TrialRow> rows = ExperimentRows(p.configs, p.options);
  const std::vector<std::size_t> which = batch.Trials(rows.size());
  std::fprintf(stderr, "sounds_good_experiment: %d configurations x %zu modes x %d trials on %s%s\n",
               p.configs, p.options.modes.size(), p.options.trials, setup.map_file.c_str(),
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
  const Protocol p = ParseProtocol(batch.MergedArgs(shards));
  std::vector<TrialRow> rows = ExperimentRows(p.configs, p.options);
  const std::vector<std::string>& records = shards.Records(rows.size());
  shards.CopyFiles(p.out_dir);
  Report(p, rows, records, [&](std::size_t i) { return shards.Where(i); });
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const ToolArgs args("sounds_good_experiment", kUsage, argc, argv, {"--quick", "--merge"});
  const BatchRun batch(args, {"--out", "--threads"});
  try {
    return batch.merging() ? Merge(batch) : Run(args, batch);
  } catch (const grid::InputError& e) {
    std::cerr << "sounds_good_experiment: " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "sounds_good_experiment: " << e.what() << "\n";
  }
  return 1;
}
