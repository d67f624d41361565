#pragma once

// charging_experiment's command line (charging_experiment.cpp), parsed apart from the tool so
// that tests and the fuzzer can call it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "charging_demo/charging_trial.h"
#include "experiment_channel_args.h"
#include "charging_demo/charging_world.h"
#include "tool_args/shard.h"
#include "tool_args/tool_args.h"

namespace charging_demo::tools {

// What the command line asks for.
struct Protocol {
  std::string world_file, map_file, out_dir, timeline;
  ChargingWorldOptions placement;
  double hours = 2.0, hearing = 15.0;
  bool hearing_given = false;
  audio_propagation::tools::ExperimentChannel channel;
  int seeds = 10, threads = 0;
  std::uint32_t first_seed = 1;
  ChargingTrialOptions options;
};

// The command: a run (`run`), or the merge of shards (the merge parses the shards' options with
// ParseProtocol).
using ExperimentCommand = multirobot_audio::tools::BatchCommand<Protocol>;

// Both throw multirobot_audio::tools::UsageError naming what they refuse (an option out of its
// range in the options' own words, without the usage line), HelpRequested for -h.
ExperimentCommand ParseExperimentArgs(const std::vector<std::string>& words);
Protocol ParseProtocol(const multirobot_audio::tools::ToolArgs& args, const multirobot_audio::tools::BatchRun& batch);

}  // namespace charging_demo::tools
