#include "sounds_good_explorer/statistics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sounds_good_explorer {
namespace {

TEST(Statistics, SummaryOfAKnownSample) {
  const SampleSummary s = Summarize({2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0});
  EXPECT_EQ(s.n, 8);
  EXPECT_DOUBLE_EQ(s.mean, 5.0);
  EXPECT_NEAR(s.sd, std::sqrt(32.0 / 7.0), 1e-12);
  // t(0.975, 7) = 2.364624...
  EXPECT_NEAR(s.ci95, 2.364624 * std::sqrt(32.0 / 7.0) / std::sqrt(8.0), 1e-5);
  EXPECT_EQ(Summarize({}).n, 0);
  EXPECT_EQ(Summarize({3.0}).sd, 0.0);
}

TEST(Statistics, StudentTTestMatchesAHandComputation) {
  // Means 3 and 6, variances 2.5 and 10, pooled 6.25, standard error sqrt(6.25 * 0.4):
  // t = -3 / 1.5811 = -1.8974 with 8 degrees of freedom, two-tailed p = 0.0944.
  const TTest test = StudentTTest({1, 2, 3, 4, 5}, {2, 4, 6, 8, 10});
  EXPECT_NEAR(test.t, -1.897367, 1e-5);
  EXPECT_NEAR(test.p, 0.09434, 2e-4);
  EXPECT_DOUBLE_EQ(test.gain, 3.0 / 6.0 - 1.0);
  // The other way round: method 2 faster, positive t and gain.
  const TTest back = StudentTTest({2, 4, 6, 8, 10}, {1, 2, 3, 4, 5});
  EXPECT_NEAR(back.t, 1.897367, 1e-5);
  EXPECT_DOUBLE_EQ(back.gain, 1.0);
}

TEST(Statistics, FarApartSamplesAreSignificantAndEqualOnesAreNot) {
  EXPECT_LT(StudentTTest({10, 11, 12, 10, 11}, {20, 21, 19, 22, 20}).p, 1e-6);
  EXPECT_GT(StudentTTest({10, 11, 12}, {11, 12, 10}).p, 0.99);
  EXPECT_EQ(StudentTTest({5, 5, 5}, {5, 5}).p, 1.0);
  EXPECT_EQ(StudentTTest({5, 5, 5}, {4, 4}).p, 0.0);
}

TEST(Statistics, StoufferCombinesConsistentEvidence) {
  // Three tests each at p = 0.1 in the same direction: z = 1.6449 each, Z = 2.849, p = 0.0044.
  const TTest one{2.0, 0.1, 0.5};
  const CombinedTest c = Stouffer({one, one, one});
  EXPECT_NEAR(c.z, 3 * 1.644854 / std::sqrt(3.0), 1e-5);
  EXPECT_NEAR(c.p, 0.004387, 1e-5);
  EXPECT_NEAR(c.gain, 0.5, 1e-12);
  // Opposite directions cancel.
  const TTest other{-2.0, 0.1, -1.0 / 3.0};
  const CombinedTest none = Stouffer({one, other});
  EXPECT_NEAR(none.z, 0.0, 1e-9);
  EXPECT_NEAR(none.p, 1.0, 1e-9);
  EXPECT_NEAR(none.gain, 0.0, 1e-12);  // 1.5 x (2/3) = 1
  EXPECT_EQ(Stouffer({}).p, 1.0);
}

}  // namespace
}  // namespace sounds_good_explorer
