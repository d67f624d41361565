// The tools' command-line parsers (tools/audio_propagation_args.h): what they refuse, and how.
#include "audio_propagation_args.h"

#include <gtest/gtest.h>

#include "tool_args/usage_error.h"

namespace audio_propagation::tools {
namespace {

using multirobot_audio::tools::UsageError;

// The message the parser refuses `words` with.
std::string Refusal(const std::vector<std::string>& words) {
  try {
    ParseValidateArgs(words);
  } catch (const UsageError& e) {
    return e.Message();
  }
  return "accepted";
}

TEST(ValidateArgs, PredictTakesTwoPointsInOneOrTwoWords) {
  const ValidateArgs two = ParseValidateArgs({"--world", "w.yaml", "--predict", "1,2", "3.5,-4"});
  EXPECT_TRUE(two.predict);
  EXPECT_EQ(two.from, Eigen::Vector2d(1.0, 2.0));
  EXPECT_EQ(two.to, Eigen::Vector2d(3.5, -4.0));
  const ValidateArgs one = ParseValidateArgs({"--world", "w.yaml", "--predict", "1,2   3.5,-4"});
  EXPECT_EQ(one.to, Eigen::Vector2d(3.5, -4.0));
  EXPECT_NE(Refusal({"--world", "w.yaml", "--predict", "1,2"}).find("--predict: expected two points X1,Y1 X2,Y2"),
            std::string::npos);
}

// Found by fuzz/tool_args.cpp: a first point followed by spaces and nothing else threw
// std::out_of_range out of the parser (substr at npos).
TEST(ValidateArgs, PredictWithTrailingSpacesIsRefused) {
  const std::string refusal = Refusal({"--world", "w.yaml", "--predict", "1,1 "});
  EXPECT_EQ(refusal.rfind("audio_channel_validate: --predict: expected two points X1,Y1 X2,Y2\nusage: ", 0), 0u)
      << refusal;
}

}  // namespace
}  // namespace audio_propagation::tools
