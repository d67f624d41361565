// The simulated team's ranging: the real ranger fed what a real team would share, so a range
// comes only after an exchange both ways, is as good as the arrival errors allow whatever the
// sound cards' clocks, and bad options are refused by name.
#include "ranging/simulated_ranging.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace ranging {
namespace {

// Arrival errors of about +-20 us (a few mm each way), symmetric.
ArrivalErrors SmallErrors() { return ArrivalErrors{{-40e-6, -10e-6, 0.0, 10e-6, 40e-6}}; }

SimulatedRangingOptions Options() {
  SimulatedRangingOptions o;
  o.errors = SmallErrors();
  o.seed = 7;
  return o;
}

std::vector<std::uint8_t> Payload(std::size_t sender, int k) {
  return {static_cast<std::uint8_t>(sender), static_cast<std::uint8_t>(k), 0x5A, 0xA5};
}

// Robots on a line, `distance[i][j]` apart; each sends in turn every `period` s and everyone
// hears it.
void Exchange(SimulatedRanging& sim, const std::vector<std::vector<double>>& distance, int rounds, double period,
              double t0 = 0.0) {
  double t = t0;
  for (int k = 0; k < rounds; ++k) {
    for (std::size_t s = 0; s < sim.size(); ++s, t += period) {
      sim.Sent(s, Payload(s, k), t);
      for (std::size_t l = 0; l < sim.size(); ++l) {
        if (l == s) continue;
        EXPECT_TRUE(sim.Heard(l, s, Payload(s, k), distance[s][l], t + 0.5));
      }
    }
  }
}

TEST(SimulatedRangingTest, NoRangeBeforeAnExchangeBothWays) {
  SimulatedRanging sim({"a", "b"}, Options());
  sim.Sent(0, Payload(0, 0), 1.0);
  ASSERT_TRUE(sim.Heard(1, 0, Payload(0, 0), 5.0, 1.5));
  EXPECT_FALSE(sim.RangeTo(0, 1, 2.0));
  EXPECT_FALSE(sim.RangeTo(1, 0, 2.0));
  sim.Sent(1, Payload(1, 0), 3.0);
  ASSERT_TRUE(sim.Heard(0, 1, Payload(1, 0), 5.0, 3.5));
  ASSERT_TRUE(sim.RangeTo(0, 1, 4.0));
  ASSERT_TRUE(sim.RangeTo(1, 0, 4.0));
  EXPECT_NEAR(sim.RangeTo(0, 1, 4.0)->range, 5.0, 0.05);
  EXPECT_NEAR(sim.RangeTo(1, 0, 4.0)->range, 5.0, 0.05);
}

TEST(SimulatedRangingTest, ThreeRobotsRangeEachOtherDespiteTheirClocks) {
  SimulatedRangingOptions o = Options();
  o.max_clock_rate_error = 100e-6;
  SimulatedRanging sim({"a", "b", "c"}, o);
  // The clocks differ, as real sound cards do.
  EXPECT_NE(sim.clock_rate_error(0), sim.clock_rate_error(1));
  EXPECT_NE(sim.Clock(0, 10.0) - 10.0, sim.Clock(1, 10.0) - 10.0);
  const std::vector<std::vector<double>> d = {{0, 3, 12}, {3, 0, 9.5}, {12, 9.5, 0}};
  Exchange(sim, d, 6, 1.5);
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t t = 0; t < 3; ++t) {
      if (r == t) continue;
      const auto range = sim.RangeTo(r, t, 30.0);
      ASSERT_TRUE(range) << r << " to " << t;
      // 100 ppm over a 1.5-4.5 s exchange would be up to 8 cm unless the rate is learnt.
      EXPECT_NEAR(range->range, d[r][t], 0.03) << r << " to " << t;
      EXPECT_GT(range->range_std, 0.0);
    }
  }
  EXPECT_EQ(sim.refused().total(), 0u);
}

// A sound card 1000 ppm off makes every range 1000 ppm long or short until its robot has learnt
// its rate, some 30 s after it started (as a real link does against its host's clock).
TEST(SimulatedRangingTest, ARobotLearnsItsOwnCardsRate) {
  SimulatedRangingOptions o = Options();
  o.max_clock_rate_error = 1e-3;
  o.rate_report_std = 0.0;  // the teammate's rate is known exactly, and the timings too: only
  o.errors = ArrivalErrors{{0.0, 0.0}};  // the own card's rate is left
  o.ranger.samples = 1;
  SimulatedRanging sim({"a", "b"}, o);
  const double d = 150.0;
  Exchange(sim, {{0, d}, {d, 0}}, 1, 2.0, 0.0);
  const double early = sim.RangeTo(0, 1, 5.0)->range - d;
  Exchange(sim, {{0, d}, {d, 0}}, 1, 2.0, 40.0);
  const double late = sim.RangeTo(0, 1, 45.0)->range - d;
  EXPECT_NEAR(early, d * sim.clock_rate_error(0), 0.002);
  EXPECT_GT(std::abs(early), 0.01);  // the draw put this card well off
  EXPECT_LT(std::abs(late), 0.002);
}

TEST(SimulatedRangingTest, ArrivalErrorsShowInTheRanges) {
  SimulatedRangingOptions o = Options();
  o.errors = ArrivalErrors{{-2e-3, -1e-3, 0.0, 1e-3, 2e-3}};  // +-1 ms: tens of cm
  o.ranger.samples = 1;
  SimulatedRanging sim({"a", "b"}, o);
  double worst = 0.0;
  for (int k = 0; k < 20; ++k) {
    Exchange(sim, {{0, 4}, {4, 0}}, 1, 2.0, 100.0 * k);
    worst = std::max(worst, std::abs(sim.RangeTo(0, 1, 100.0 * k + 5.0)->range - 4.0));
  }
  EXPECT_GT(worst, 0.1);
  EXPECT_LT(worst, 343.0 * 2 * 2e-3);
}

TEST(SimulatedRangingTest, AReceptionOfNoKnownSendingTimesNothing) {
  SimulatedRanging sim({"a", "b"}, Options());
  sim.Sent(0, Payload(0, 0), 5.0);
  EXPECT_FALSE(sim.Heard(1, 0, Payload(0, 1), 3.0, 6.0));   // a payload never sent
  EXPECT_FALSE(sim.Heard(1, 0, Payload(0, 0), 3.0, 4.0));   // before it was sent
  EXPECT_FALSE(sim.Heard(1, 1, Payload(0, 0), 3.0, 6.0));   // by itself
  EXPECT_FALSE(sim.Heard(1, 0, Payload(0, 0), NAN, 6.0));   // no path
  EXPECT_TRUE(sim.Heard(1, 0, Payload(0, 0), 3.0, 6.0));
}

TEST(SimulatedRangingTest, ArrivalErrorsAreDrawnFromTheirQuantiles) {
  const ArrivalErrors e{{-1.0, 0.0, 0.0, 3.0}};
  std::mt19937 rng(3);
  int zero = 0, above = 0;
  for (int k = 0; k < 3000; ++k) {
    const double x = e.Draw(rng);
    ASSERT_GE(x, -1.0);
    ASSERT_LE(x, 3.0);
    zero += x == 0.0;
    above += x > 0.0;
  }
  EXPECT_NEAR(zero / 3000.0, 1.0 / 3.0, 0.05);
  EXPECT_NEAR(above / 3000.0, 1.0 / 3.0, 0.05);
}

TEST(SimulatedRangingTest, ImpossibleOptionsAreRefusedByName) {
  const auto refused = [](SimulatedRangingOptions o, const std::string& name) {
    try {
      SimulatedRanging sim({"a"}, o);
      ADD_FAILURE() << "accepted, expected a complaint about " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  SimulatedRangingOptions o = Options();
  o.errors.quantiles = {0.0};
  refused(o, "at least 2 quantiles");
  o.errors.quantiles = {0.0, -1e-3};
  refused(o, "ascending");
  o.errors.quantiles = {0.0, NAN};
  refused(o, "quantile 1");
  o = Options();
  o.max_clock_rate_error = 0.01;
  refused(o, "max_clock_rate_error");
  o = Options();
  o.rate_report_std = 0.5;
  refused(o, "rate_report_std");
  o = Options();
  o.ranger.pair_window = 0.0;
  refused(o, "pair_window");
  EXPECT_THROW(SimulatedRanging({}, Options()), std::invalid_argument);
}

}  // namespace
}  // namespace ranging
