#pragma once

// world_sim_bench's command line (world_sim_bench.cpp), parsed apart from the tool so that tests
// and the fuzzer can call it.
#include <string>
#include <vector>

#include "package_data/package_data.h"

namespace world_sim::tools {

struct WorldSimBenchArgs {
  std::string map = package_data::DataFile("maps/office.yaml");
  int robots = 20;
  double seconds = 600.0;
  unsigned seed = 1;
};

// Throws multirobot_audio::tools::UsageError naming what it refuses, HelpRequested for -h.
WorldSimBenchArgs ParseWorldSimBenchArgs(const std::vector<std::string>& words);

// Refuses the command line after parsing (a team that does not fit the map), in the parser's words.
[[noreturn]] void RefuseWorldSimBench(const std::string& problem);

}  // namespace world_sim::tools
