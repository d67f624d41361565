#include "charging_experiment_args.h"

#include <stdexcept>

#include "package_data/package_data.h"

namespace charging_demo::tools {
namespace {

using multirobot_audio::tools::BatchRun;
using multirobot_audio::tools::ToolArgs;

const std::string kUsage =
    std::string("charging_experiment [--map MAP.yaml | --world WORLD.yaml] [--robots 4] [--chargers 1]\n"
    "  [--hours 2] [--seeds 10] [--seed 1] [--out charging_results] [--timeline FILE.png]\n"
    "  [--hearing 15] [--spacing 12] [--low 0.3] [--full 0.98] [--wait-distance 1]\n"
    "  [--lock-timeout 1500] [--threads 0] ") + audio_propagation::tools::kExperimentChannelUsage +
    "\n  [--shard K/N] | --merge SHARD_DIR... [--out DIR] [--timeline FILE.png]";

}  // namespace

Protocol ParseProtocol(const ToolArgs& args, const BatchRun& batch) {
  Protocol p;
  p.world_file = args.String("--world", "");
  p.map_file = args.String("--map", package_data::DataFile("maps/office.yaml"));
  ChargingWorldOptions& placement = p.placement;
  placement.robots = static_cast<int>(args.Int("--robots", placement.robots, 1, 255));
  placement.chargers = static_cast<int>(args.Int("--chargers", placement.chargers, 1, 1000));
  placement.charger_spacing = args.Double("--spacing", placement.charger_spacing, 0.0, 1e6);
  p.hours = args.Double("--hours", 2.0, 1e-3, 1000.0);
  p.seeds = static_cast<int>(args.Int("--seeds", 10, 1, 100000));
  p.first_seed = static_cast<std::uint32_t>(args.Int("--seed", 1, 0, 4294967295L));
  p.hearing = args.Double("--hearing", 15.0, 0.0, 1e6);
  p.hearing_given = !args.String("--hearing", "").empty();
  ChargingTrialOptions& options = p.options;
  options.duration = p.hours * 3600.0;
  ChargingOptions& charging = options.controller.charging;
  charging.low_battery = args.Double("--low", charging.low_battery, -1e9, 1e9);
  charging.full_battery = args.Double("--full", charging.full_battery, -1e9, 1e9);
  charging.wait_distance = args.Double("--wait-distance", charging.wait_distance, -1e9, 1e9);
  charging.lock_timeout = args.Double("--lock-timeout", charging.lock_timeout, -1e9, 1e9);
  p.threads = static_cast<int>(args.Int("--threads", 0, 0, 256));
  p.out_dir = args.String("--out", "charging_results");
  p.timeline = args.String("--timeline", "");
  p.channel = audio_propagation::tools::ParseExperimentChannel(args, options.channel);
  if (!p.world_file.empty() && (!args.String("--robots", "").empty() || !args.String("--chargers", "").empty() ||
                                !args.String("--map", "").empty() || !args.String("--spacing", "").empty()))
    args.Fail("--world gives the robots, chargers and map: drop --robots, --chargers, --map and --spacing");
  if (batch.sharded() && !p.timeline.empty())
    args.Fail("--timeline: give it to --merge, which draws the first seed's trial from the shards");
  args.CheckAllUsed();
  // The options' own checks name the field (a threshold outside (0, 1), ...) before any work,
  // in their own words (no usage line).
  charging.chargers = {placement.first_marker};
  try {
    ValidateOptions(placement);
    ValidateOptions(options.controller);
    ValidateOptions(options);
  } catch (const std::invalid_argument& e) {
    throw multirobot_audio::tools::UsageError(args.program(), e.what());
  }
  return p;
}

ExperimentCommand ParseExperimentArgs(const std::vector<std::string>& words) {
  const ToolArgs args("charging_experiment", kUsage, words, {"--merge", audio_propagation::tools::kLinkFateSwitch});
  return multirobot_audio::tools::ParseBatchCommand<Protocol>(args, {"--out", "--threads", "--timeline"},
                                                               ParseProtocol);
}

}  // namespace charging_demo::tools
