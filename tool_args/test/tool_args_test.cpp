#include "tool_args/tool_args.h"

#include <sstream>

#include <gtest/gtest.h>

namespace multirobot_audio::tools {
namespace {

TEST(ToolArgs, RefusesWithAUsageErrorInsteadOfExiting) {
  const ToolArgs args("tool", "tool --n N", std::vector<std::string>{"--n", "x"});
  try {
    args.Int("--n", 1, 0, 9);
    FAIL() << "a bad number was accepted";
  } catch (const UsageError& e) {
    EXPECT_EQ(e.Message(), "tool: --n: expected a whole number from 0 to 9, got x\nusage: tool --n N");
  }
}

TEST(ToolArgs, HelpIsAnAnswerNotAnError) {
  try {
    ToolArgs("tool", "tool --n N", std::vector<std::string>{"--n", "1", "-h"});
    FAIL() << "-h was not answered";
  } catch (const HelpRequested& help) {
    EXPECT_EQ(help.usage(), "tool --n N");
  }
}

TEST(RunTool, PrintsRefusalsAndHelpWithTheirExitStatus) {
  std::ostringstream out, err;
  auto* old_out = std::cout.rdbuf(out.rdbuf());
  auto* old_err = std::cerr.rdbuf(err.rdbuf());
  const int refused = RunTool([] () -> int { throw UsageError("tool", "--x: no", "tool --x X"); });
  const int plain = RunTool([] () -> int { throw UsageError("tool", "file.yaml: bad"); });
  const int help = RunTool([] () -> int { throw HelpRequested("tool --x X"); });
  const int ran = RunTool([] { return 3; });
  std::cout.rdbuf(old_out);
  std::cerr.rdbuf(old_err);
  EXPECT_EQ(refused, 1);
  EXPECT_EQ(plain, 1);
  EXPECT_EQ(help, 0);
  EXPECT_EQ(ran, 3);
  EXPECT_EQ(err.str(), "tool: --x: no\nusage: tool --x X\ntool: file.yaml: bad\n");
  EXPECT_EQ(out.str(), "usage: tool --x X\n");
}

// A usage error is not a std::exception, so that the tools' run-time handlers let it through.
TEST(RunTool, UsageErrorsPassStdExceptionHandlers) {
  std::ostringstream err;
  auto* old_err = std::cerr.rdbuf(err.rdbuf());
  const int status = RunTool([]() -> int {
    try {
      ToolUsage{"tool", "tool"}.Fail("late");
    } catch (const std::exception&) {
      return 2;
    }
  });
  std::cerr.rdbuf(old_err);
  EXPECT_EQ(status, 1);
  EXPECT_EQ(err.str(), "tool: late\nusage: tool\n");
}

}  // namespace
}  // namespace multirobot_audio::tools
