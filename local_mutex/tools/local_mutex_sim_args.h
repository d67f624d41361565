#pragma once

// local_mutex_sim's command line (local_mutex_sim.cpp), parsed apart from the tool so that tests
// and the fuzzer can call it.
#include <optional>
#include <string>
#include <vector>

#include "experiment_channel_args.h"
#include "local_mutex/scenarios.h"
#include "local_mutex/team_sim.h"
#include "tool_args/shard.h"
#include "tool_args/tool_args.h"

namespace local_mutex::tools {

// What a run asks for: a scenario, N random trials, the sweep or the failure bound.
struct SimRequest {
  std::string scenario, timeline, out;
  int trial_count = 0, sweep = 0, bound = 0;  // trials in all, or per cell of the sweep or the bound
  double rho = 1e-3;                          // the bound's failure rate to choose n for
  TeamSimOptions options;  // with the acoustic channel, its table and acoustics are loaded by the tool
  TrialOptions trials;
  audio_propagation::tools::ExperimentChannel channel;
};

// The command: a run (`run`), or the merge of shards (the merge parses the shards' options with
// ParseSimRequest).
using SimCommand = multirobot_audio::tools::BatchCommand<SimRequest>;

// Both throw multirobot_audio::tools::UsageError naming what they refuse, HelpRequested for -h.
SimCommand ParseSimArgs(const std::vector<std::string>& words);
SimRequest ParseSimRequest(const multirobot_audio::tools::ToolArgs& args, const multirobot_audio::tools::BatchRun& batch);

}  // namespace local_mutex::tools
