// A sound card's rate against the host's clock: found to a few ppm from reads that come late and
// irregularly, forgotten when the card reopens, and never made up from too little.
#include "nava_modem/card_rate.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace nava_modem {
namespace {

// Reads every ~21 ms for `seconds` of a card `ppm` fast, each up to 5 ms late, through a sound
// server that hands the captured frames on in 50 ms chunks (PulseAudio at 50 ms of latency): the
// count a link sees lags the card's by up to a chunk.
void Feed(CardRateTracker& tracker, double start, double seconds, double ppm, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> late(0.0, 0.005);
  for (double t = 0.0; t < seconds; t += 0.0213) {
    const double seen = t + late(rng);
    const double chunked = std::floor(seen / 0.05) * 0.05;
    tracker.Add(start + seen, static_cast<std::int64_t>(std::floor(chunked * 48000.0 * (1.0 + ppm * 1e-6))));
  }
}

TEST(CardRateTest, FindsTheCardsRateToAFewPpm) {
  for (double ppm : {-95.0, -12.0, 0.0, 40.0, 100.0}) {
    CardRateTracker tracker(CardRateOptions{48000.0});
    Feed(tracker, 1000.0, 120.0, ppm, 3);
    EXPECT_NEAR(tracker.rate_error() * 1e6, ppm, 3.0) << ppm;
  }
}

TEST(CardRateTest, NothingUntilTheReadsSpanEnoughAndAfterAReopen) {
  CardRateTracker tracker(CardRateOptions{48000.0});
  EXPECT_TRUE(std::isnan(tracker.rate_error()));
  Feed(tracker, 0.0, 25.0, 50.0, 1);
  EXPECT_TRUE(std::isnan(tracker.rate_error()));  // 25 s: not yet
  Feed(tracker, 25.0, 10.0, 50.0, 2);
  // The count goes on from where it was: a frames count of 0 again is a reopened card.
  EXPECT_TRUE(std::isnan(tracker.rate_error()));
  Feed(tracker, 35.0, 40.0, 50.0, 3);
  EXPECT_NEAR(tracker.rate_error() * 1e6, 50.0, 5.0);
  tracker.Reset();
  EXPECT_TRUE(std::isnan(tracker.rate_error()));
  // A line no card could give (1 %): none.
  Feed(tracker, 100.0, 40.0, 10000.0, 4);
  EXPECT_TRUE(std::isnan(tracker.rate_error()));
}

TEST(CardRateTest, ImpossibleOptionsAreRefused) {
  EXPECT_THROW(CardRateTracker(CardRateOptions{0.0}), std::invalid_argument);
  CardRateOptions o;
  o.min_span = 200.0;
  EXPECT_THROW(CardRateTracker{o}, std::invalid_argument);
  o = CardRateOptions{};
  o.max_error = 0.0;
  EXPECT_THROW(CardRateTracker{o}, std::invalid_argument);
  o = CardRateOptions{};
  o.spacing = -1.0;
  EXPECT_THROW(CardRateTracker{o}, std::invalid_argument);
}

}  // namespace
}  // namespace nava_modem
