#include "world_sim_bench_args.h"

#include <cstdint>

#include "tool_args/tool_args.h"
#include "tool_args/usage_error.h"

namespace world_sim::tools {
namespace {

const char* kUsage = "world_sim_bench [--map MAP.yaml] [--robots N] [--seconds S] [--seed K]";

}  // namespace

void RefuseWorldSimBench(const std::string& problem) {
  throw multirobot_audio::tools::UsageError("world_sim_bench", problem, kUsage);
}

WorldSimBenchArgs ParseWorldSimBenchArgs(const std::vector<std::string>& words) {
  const multirobot_audio::tools::ToolArgs args("world_sim_bench", kUsage, words);
  WorldSimBenchArgs a;
  a.map = args.String("--map", a.map);
  a.robots = static_cast<int>(args.Int("--robots", a.robots, 1, 10000));
  // A finite run: a bench that never ends measures nothing (a simulated year at most).
  a.seconds = args.Double("--seconds", a.seconds, 0.001, 3.2e7);
  a.seed = static_cast<unsigned>(args.Int("--seed", a.seed, 0, UINT32_MAX));
  args.CheckAllUsed();
  return a;
}

}  // namespace world_sim::tools
