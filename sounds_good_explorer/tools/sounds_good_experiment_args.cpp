#include "sounds_good_experiment_args.h"

#include <sstream>

#include "package_data/package_data.h"

namespace sounds_good_explorer::tools {
namespace {

using multirobot_audio::tools::BatchRun;
using multirobot_audio::tools::ToolArgs;

const std::string kUsage =
    std::string("sounds_good_experiment (--map MAP.yaml | --worlds W1.yaml,W2.yaml | --quick) [--out DIR]\n"
    "  [--configs 10] [--modes none,bidirectional,omni] [--trials 20] [--robots 5] [--jobs 20]\n"
    "  [--work 30] [--hearing 15] [--ir-range 1.5] [--camera-range 5] [--cap 20000] [--seed 1]\n"
    "  [--threads 0] [--chart-config 9] [--audio-weight 3] [--noise-std 0.3]\n"
    "  [--announce-period 2] [--announce-window 10] [--arrive-radius 0.6]\n"
    "  ") + audio_propagation::tools::kExperimentChannelUsage + "\n"
    "  [--shard K/N] | --merge SHARD_DIR... [--out DIR]";

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');)
    if (!part.empty()) parts.push_back(part);
  return parts;
}

}  // namespace

Protocol ParseProtocol(const ToolArgs& args) {
  Protocol p;
  const bool quick = args.Switch("--quick");
  ExperimentOptions& options = p.options;
  TrialOptions& trial = options.trial;
  ExplorerOptions& explorer = trial.explorer;
  const std::string worlds = args.String("--worlds", "");
  p.map_file = args.String("--map", quick ? package_data::DataFile("maps/office.yaml") : "");
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
  p.channel = audio_propagation::tools::ParseExperimentChannel(args, trial.channel);
  args.CheckAllUsed();
  p.placement.source = explorer.task.source;
  p.placement.sink = explorer.task.sink;
  return p;
}

ExperimentCommand ParseExperimentArgs(const std::vector<std::string>& words) {
  const ToolArgs args("sounds_good_experiment", kUsage, words, {"--quick", "--merge", audio_propagation::tools::kLinkFateSwitch});
  return multirobot_audio::tools::ParseBatchCommand<Protocol>(
      args, {"--out", "--threads"}, [](const ToolArgs& a, const BatchRun&) { return ParseProtocol(a); });
}

}  // namespace sounds_good_explorer::tools
