#include <gtest/gtest.h>

#include "tool_args/usage_error.h"
#include "world_sim_bench_args.h"

namespace world_sim::tools {
namespace {

using multirobot_audio::tools::HelpRequested;
using multirobot_audio::tools::UsageError;

TEST(WorldSimBenchArgs, ReadsEachFlag) {
  const WorldSimBenchArgs a =
      ParseWorldSimBenchArgs({"--map", "room.yaml", "--robots", "3", "--seconds", "2.5", "--seed", "7"});
  EXPECT_EQ(a.map, "room.yaml");
  EXPECT_EQ(a.robots, 3);
  EXPECT_DOUBLE_EQ(a.seconds, 2.5);
  EXPECT_EQ(a.seed, 7u);
}

TEST(WorldSimBenchArgs, RefusesARunThatNeverEnds) {
  for (const char* seconds : {"inf", "nan", "0", "-1", "1e300"}) {
    EXPECT_THROW(ParseWorldSimBenchArgs({"--seconds", seconds}), UsageError) << seconds;
  }
}

TEST(WorldSimBenchArgs, RefusesBadCountsAndUnknownFlags) {
  EXPECT_THROW(ParseWorldSimBenchArgs({"--robots", "0"}), UsageError);
  EXPECT_THROW(ParseWorldSimBenchArgs({"--robots", "2x"}), UsageError);
  EXPECT_THROW(ParseWorldSimBenchArgs({"--seed", "-1"}), UsageError);
  EXPECT_THROW(ParseWorldSimBenchArgs({"--speed", "2"}), UsageError);
  EXPECT_THROW(ParseWorldSimBenchArgs({"--robots"}), UsageError);
  EXPECT_THROW(ParseWorldSimBenchArgs({"extra"}), UsageError);
  EXPECT_THROW(ParseWorldSimBenchArgs({"-h"}), HelpRequested);
}

}  // namespace
}  // namespace world_sim::tools
