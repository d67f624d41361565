#include "audio_propagation/microphone.h"

#include <cmath>

#include <gtest/gtest.h>

namespace audio_propagation {
namespace {

using world_sim::Microphone;

TEST(Microphone, OmniReportsTheTrueDirectionInTheRobotFrame) {
  std::mt19937 rng(1);
  EXPECT_NEAR(SenseDirection(Microphone::kOmni, M_PI / 2, M_PI / 2, 0.0, rng), 0.0, 1e-12);
  EXPECT_NEAR(SenseDirection(Microphone::kOmni, M_PI, M_PI / 2, 0.0, rng), M_PI / 2, 1e-12);
  EXPECT_NEAR(SenseDirection(Microphone::kOmni, -3.0, 3.0, 0.0, rng), -6.0 + 2 * M_PI, 1e-12);
}

TEST(Microphone, OmniNoiseHasTheStatedSpread) {
  std::mt19937 rng(2);
  double sum = 0.0, sum2 = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double e = SenseDirection(Microphone::kOmni, 0.3, 0.0, 0.1, rng) - 0.3;
    sum += e;
    sum2 += e * e;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.005);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.1, 0.005);
}

TEST(Microphone, BidirectionalTellsFrontFromBack) {
  std::mt19937 rng(3);
  EXPECT_EQ(SenseDirection(Microphone::kBidirectional, 0.2, 0.0, 0.0, rng), 0.0);
  EXPECT_EQ(SenseDirection(Microphone::kBidirectional, -1.5, 0.0, 0.0, rng), 0.0);
  EXPECT_EQ(SenseDirection(Microphone::kBidirectional, 2.0, 0.0, 0.0, rng), M_PI);
  EXPECT_EQ(SenseDirection(Microphone::kBidirectional, 0.0, M_PI, 0.0, rng), M_PI);  // behind it
}

TEST(Microphone, NoneAndUndefinedGiveNaN) {
  std::mt19937 rng(4);
  EXPECT_TRUE(std::isnan(SenseDirection(Microphone::kNone, 1.0, 0.0, 0.0, rng)));
  EXPECT_TRUE(std::isnan(SenseDirection(Microphone::kOmni, std::nan(""), 0.0, 0.1, rng)));
}

}  // namespace
}  // namespace audio_propagation
