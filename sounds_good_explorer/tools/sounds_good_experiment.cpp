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
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
#include "tool_args/tool_args.h"
#include "world_sim/world_file.h"

namespace {

using namespace sounds_good_explorer;
namespace fs = std::filesystem;

const char* kUsage =
    "sounds_good_experiment (--map MAP.yaml | --worlds W1.yaml,W2.yaml | --quick) [--out DIR]\n"
    "  [--configs 10] [--modes none,bidirectional,omni] [--trials 20] [--robots 5] [--jobs 20]\n"
    "  [--work 30] [--hearing 15] [--ir-range 1.5] [--camera-range 5] [--cap 20000] [--seed 1]\n"
    "  [--threads 0] [--chart-config 9] [--audio-weight 3] [--noise-std 0.3]\n"
    "  [--announce-period 2] [--announce-window 10] [--arrive-radius 0.6]\n"
    "  [--channel threshold|acoustic] [--profile nava|room] [--table FILE] [--acoustics WORLD.yaml]";

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

int Run(const multirobot_audio::tools::ToolArgs& args) {
  const bool quick = args.Switch("--quick");
  ExperimentOptions options;
  TrialOptions& trial = options.trial;
  ExplorerOptions& explorer = trial.explorer;
  const std::string worlds = args.String("--worlds", "");
  std::string map_file = args.String("--map", quick ? MULTIROBOT_AUDIO_MAPS_DIR "/office.yaml" : "");
  if (worlds.empty() && map_file.empty()) args.Fail("give --map, --worlds or --quick");
  if (!worlds.empty() && !args.String("--map", "").empty()) args.Fail("give --map or --worlds, not both");
  if (!worlds.empty() && Split(worlds).empty()) args.Fail("--worlds: expected world files separated by commas, got '" + worlds + "'");
  if (!worlds.empty()) {
    if (quick) args.Fail("--quick makes configurations; give --worlds without it");
    for (const char* flag : {"--configs", "--robots", "--ir-range", "--camera-range"})
      if (!args.String(flag, "").empty())
        args.Fail(std::string(flag) + " makes configurations; the world files given by --worlds are used as they are");
  }

  const int configs = static_cast<int>(args.Int("--configs", quick ? 3 : 10, 1, 1000));
  options.trials = static_cast<int>(args.Int("--trials", quick ? 6 : 20, 1, 100000));
  options.modes.clear();
  for (const std::string& name : Split(args.String("--modes", "none,bidirectional,omni"))) {
    const auto mode = ParseListenMode(name);
    if (!mode) args.Fail("--modes: expected none, bidirectional or omni, got '" + name + "'");
    options.modes.push_back(*mode);
  }
  if (options.modes.empty()) args.Fail("--modes: expected at least one mode");
  ConfigurationOptions placement;
  placement.robots = static_cast<int>(args.Int("--robots", 5, 1, 200));
  trial.jobs = static_cast<int>(args.Int("--jobs", quick ? 8 : 20, 1, 100000));
  explorer.task.work_time = args.Double("--work", 30.0, 0.0, 1e6);
  const double hearing = args.Double("--hearing", 15.0, 0.0, 1e4);
  world_sim::RobotModel body;
  // The thesis's robots never ran flat; world_sim's do (about two hours), which would stop long
  // "no audio" trials. Generated configurations carry no battery drain.
  body.battery.idle_drain = 0.0;
  body.battery.motion_drain = 0.0;
  body.ir_range = args.Double("--ir-range", 1.5, 0.01, 100.0);
  body.camera_range = args.Double("--camera-range", 5.0, 0.01, 1000.0);
  trial.time_cap = args.Double("--cap", 20000.0, 1.0, 1e8);
  options.seed = static_cast<std::uint32_t>(args.Int("--seed", 1, 0, 4294967295L));
  options.threads = static_cast<int>(args.Int("--threads", 0, 0, 1024));
  const int chart_config = static_cast<int>(args.Int("--chart-config", 9, 1, 1000));
  explorer.frontier.audio_weight = args.Double("--audio-weight", explorer.frontier.audio_weight, 0.0, 1e6);
  explorer.frontier.noise_std = args.Double("--noise-std", explorer.frontier.noise_std, 0.0, 1e6);
  explorer.task.announce_period = args.Double("--announce-period", explorer.task.announce_period, 0.01, 1e6);
  explorer.task.announce_window = args.Double("--announce-window", explorer.task.announce_window, 0.0, 1e6);
  explorer.task.arrive_radius = args.Double("--arrive-radius", explorer.task.arrive_radius, 0.01, 100.0);
  const std::string out_dir = args.String("--out", "sounds_good_results");
  const std::string channel = args.String("--channel", "threshold");
  if (channel != "threshold" && channel != "acoustic") args.Fail("--channel: expected threshold or acoustic, got '" + channel + "'");
  const std::string profile_name = args.String("--profile", "nava");
  const auto profile = nava_modem::ParseProfile(profile_name);
  if (!profile) args.Fail(std::string("--profile: expected ") + nava_modem::kProfileNames + ", got '" + profile_name + "'");
  nava_modem::UseProfileTiming(*profile, {}, trial.channel.mac);
  const std::string table_file = args.String("--table", "");
  const std::string acoustics_file = args.String("--acoustics", "");
  if (channel != "acoustic" && (!table_file.empty() || !acoustics_file.empty())) {
    args.Fail(std::string(table_file.empty() ? "--acoustics" : "--table") + " is for --channel acoustic");
  }
  args.CheckAllUsed();
  placement.source = explorer.task.source;
  placement.sink = explorer.task.sink;

  Setup setup;
  if (!worlds.empty()) {
    setup = LoadWorlds(Split(worlds), explorer.task);
  } else {
    setup.map_file = fs::absolute(map_file).lexically_normal().string();
    setup.map = grid::LoadMapFile(setup.map_file);
    std::mt19937 rng(options.seed);
    for (int c = 0; c < configs; ++c)
      setup.configs.push_back(RandomConfiguration(setup.map, setup.map_file, body, placement, rng));
  }
  if (channel == "acoustic") {
    trial.decode_table = std::make_shared<const audio_propagation::DecodeTable>(audio_propagation::LoadDecodeTable(
        table_file.empty() ? audio_propagation::ShippedDecodeTable(profile_name) : table_file, profile_name));
    if (!acoustics_file.empty()) {
      const world_sim::LoadedWorld source = world_sim::LoadWorldFile(acoustics_file, setup.map_file);
      if (!source.config.acoustics) throw grid::InputError(acoustics_file, "acoustics", "expected an acoustics section");
      for (world_sim::WorldConfig& c : setup.configs) c.acoustics = source.config.acoustics;
    }
    for (std::size_t c = 0; c < setup.configs.size(); ++c) {
      if (!setup.configs[c].acoustics) {
        throw grid::InputError(worlds.empty() ? "--acoustics" : Split(worlds)[c], "acoustics",
                               "--channel acoustic needs an acoustics section (give --acoustics WORLD.yaml)");
      }
      world_sim::ValidateWorld(acoustics_file.empty() ? Split(worlds)[c] : acoustics_file, setup.configs[c], setup.map);
    }
  }
  const int config_count = static_cast<int>(setup.configs.size());
  if (chart_config > config_count && !args.String("--chart-config", "").empty())
    args.Fail("--chart-config: expected a configuration from 1 to " + std::to_string(config_count) +
              ", got " + std::to_string(chart_config));

  fs::create_directories(fs::path(out_dir) / "configs");
  for (int c = 0; c < config_count; ++c) {
    char name[32];
    std::snprintf(name, sizeof name, "config_%02d.yaml", c + 1);
    world_sim::SaveWorldFile((fs::path(out_dir) / "configs" / name).string(), setup.configs[c]);
  }

  audio_propagation::PropagationOptions audio;
  audio.max_range = hearing;
  if (trial.decode_table) {
    // The acoustic model judges every path: no hearing range unless one is asked for, and paths
    // down to 30 dB under the quietest world's ambient noise.
    if (args.String("--hearing", "").empty()) audio.max_range = 0.0;
    for (const world_sim::WorldConfig& c : setup.configs)
      audio.threshold_db = std::min(audio.threshold_db, audio_propagation::AcousticThresholdDb(*c.acoustics));
  }
  const audio_propagation::PropagationModel model(setup.map, audio);
  std::fprintf(stderr, "sounds_good_experiment: %d configurations x %zu modes x %d trials on %s\n",
               config_count, options.modes.size(), options.trials, setup.map_file.c_str());
  multirobot_audio::tools::ProgressBar bar;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<TrialRow> rows = RunExperiment(setup.map, setup.configs, model, options, bar);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const fs::path out(out_dir);
  WriteTrialsCsv((out / "trials.csv").string(), rows);
  WriteJobsCsv((out / "jobs.csv").string(), rows);
  const std::string table31 = Table31(rows, options.modes, config_count);
  const std::string table32 = Table32(rows, options.modes, config_count);
  WriteText((out / "table_3_1.md").string(), table31);
  WriteText((out / "table_3_2.md").string(), table32);
  WriteTeamTimeChart((out / "figure_3_6b.png").string(), rows, options.modes, config_count);
  WriteJobTimeChart((out / "figure_3_6a.png").string(), rows, options.modes,
                    std::min(chart_config, config_count), trial.jobs);
  int censored = 0;
  for (const TrialRow& r : rows) censored += r.result.censored;
  std::printf("Table 3.1: time (s) for the team to finish %d jobs\n\n%s\n", trial.jobs, table31.c_str());
  std::printf("Table 3.2: two-tailed Student's t-test per pair of modes\n\n%s\n", table32.c_str());
  std::printf("%s", Verdict(rows, options.modes, config_count).c_str());
  std::printf("trials %zu censored %d wall_s %.1f out %s\n", rows.size(), censored, wall,
              out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const multirobot_audio::tools::ToolArgs args("sounds_good_experiment", kUsage, argc, argv, {"--quick"});
  try {
    return Run(args);
  } catch (const grid::InputError& e) {
    std::cerr << "sounds_good_experiment: " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "sounds_good_experiment: " << e.what() << "\n";
  }
  return 1;
}
