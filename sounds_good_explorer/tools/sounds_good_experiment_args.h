#pragma once

// sounds_good_experiment's command line (sounds_good_experiment.cpp), parsed apart from the tool
// so that tests and the fuzzer can call it.
#include <optional>
#include <string>
#include <vector>

#include "experiment_channel_args.h"
#include "sounds_good_explorer/configurations.h"
#include "sounds_good_explorer/experiment.h"
#include "tool_args/shard.h"
#include "tool_args/tool_args.h"
#include "world_sim/world_config.h"

namespace sounds_good_explorer::tools {

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
  std::string out_dir;
  audio_propagation::tools::ExperimentChannel channel;
};

// The command: a run (`run`), or the merge of shards (the merge parses the shards' options with
// ParseProtocol).
using ExperimentCommand = multirobot_audio::tools::BatchCommand<Protocol>;

// Both throw multirobot_audio::tools::UsageError naming what they refuse, HelpRequested for -h.
ExperimentCommand ParseExperimentArgs(const std::vector<std::string>& words);
Protocol ParseProtocol(const multirobot_audio::tools::ToolArgs& args);

}  // namespace sounds_good_explorer::tools
