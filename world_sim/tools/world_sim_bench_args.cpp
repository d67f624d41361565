#include "world_sim_bench_args.h"

#include <cstdlib>

#include "tool_args/usage_error.h"

namespace world_sim::tools {
namespace {

const char* kUsage = "world_sim_bench [--map MAP.yaml] [--robots N] [--seconds S] [--seed K]";

}  // namespace

void RefuseWorldSimBench(const std::string& problem) {
  throw multirobot_audio::tools::UsageError("world_sim_bench", problem, kUsage);
}

WorldSimBenchArgs ParseWorldSimBenchArgs(const std::vector<std::string>& words) {
  WorldSimBenchArgs a;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& flag = words[i];
    if (flag == "-h" || flag == "--help") throw multirobot_audio::tools::HelpRequested(kUsage);
    if (i + 1 >= words.size()) RefuseWorldSimBench(flag + " needs a value");
    const std::string& value = words[++i];
    char* end = nullptr;
    if (flag == "--map") {
      a.map = value;
    } else if (flag == "--robots") {
      a.robots = static_cast<int>(std::strtol(value.c_str(), &end, 10));
      if (*end || a.robots < 1) RefuseWorldSimBench("--robots: expected a whole number >= 1, got " + value);
    } else if (flag == "--seconds") {
      a.seconds = std::strtod(value.c_str(), &end);
      if (*end || !(a.seconds > 0)) RefuseWorldSimBench("--seconds: expected a positive number, got " + value);
    } else if (flag == "--seed") {
      a.seed = static_cast<unsigned>(std::strtoul(value.c_str(), &end, 10));
      if (*end) RefuseWorldSimBench("--seed: expected a whole number, got " + value);
    } else {
      RefuseWorldSimBench("unknown option " + flag);
    }
  }
  return a;
}

}  // namespace world_sim::tools
