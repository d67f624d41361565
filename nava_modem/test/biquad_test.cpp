// Butterworth filters from second-order sections: their gains where a Butterworth's are known,
// zero phase forwards and backwards, and the refusals.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/biquad.h"

namespace nava_modem {
namespace {

constexpr double kRate = 48000.0;

// The steady gain of the sections at `hz` (a whole number), dB: a tone's power over the second
// half second, after half a second of settling.
double GainDb(std::vector<Biquad> sections, double hz) {
  double power = 0.0;
  const int n = static_cast<int>(kRate);
  for (int k = 0; k < n; ++k) {
    double y = std::sin(2.0 * M_PI * hz * k / kRate);
    for (Biquad& s : sections) y = s.Run(y);
    if (k >= n / 2) power += y * y;
  }
  return 10.0 * std::log10(power / (n / 2) * 2.0);
}

TEST(BiquadTest, ButterworthGainsAreFlatThenThreeDbDownAtTheCornerThenFallBySixDbAnOctaveAnOrder) {
  for (int order : {2, 4, 8}) {
    const std::vector<Biquad> low = Butterworth(kRate, 1000.0, false, order);
    ASSERT_EQ(low.size(), static_cast<std::size_t>(order / 2));
    EXPECT_NEAR(GainDb(low, 100.0), 0.0, 0.05) << order;
    EXPECT_NEAR(GainDb(low, 1000.0), -3.01, 0.05) << order;
    // Two octaves up: 12 dB an octave an order's pair, more where the bilinear
    // transform squeezes the octave towards half the rate.
    EXPECT_LT(GainDb(low, 4000.0), -12.04 * order + 0.5) << order;
    EXPECT_GT(GainDb(low, 4000.0), -12.04 * order - 3.0) << order;
    const std::vector<Biquad> high = Butterworth(kRate, 1000.0, true, order);
    EXPECT_NEAR(GainDb(high, 10000.0), 0.0, 0.05) << order;
    EXPECT_NEAR(GainDb(high, 1000.0), -3.01, 0.05) << order;
    EXPECT_NEAR(GainDb(high, 250.0), -12.04 * order, 1.5) << order;
  }
}

TEST(BiquadTest, ForwardsAndBackwardsKeepsAnImpulseWhereItWas) {
  std::vector<double> x(4800, 0.0);
  x[2400] = 1.0;
  std::vector<Biquad> band = Butterworth(kRate, 600.0, true, 4);
  const std::vector<Biquad> low = Butterworth(kRate, 5400.0, false, 4);
  band.insert(band.end(), low.begin(), low.end());
  const std::vector<double> y = FilterForwardBackward(x, band);
  ASSERT_EQ(y.size(), x.size());
  std::size_t largest = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    if (std::abs(y[k]) > std::abs(y[largest])) largest = k;
  }
  EXPECT_EQ(largest, 2400u);
  for (std::size_t d = 1; d < 1000; ++d) EXPECT_NEAR(y[2400 - d], y[2400 + d], 1e-9) << d;  // symmetric
  // The one-way filter delays it instead.
  std::vector<double> one_way = x;
  for (Biquad s : band) {
    for (double& v : one_way) v = s.Run(v);
  }
  std::size_t one_way_largest = 0;
  for (std::size_t k = 0; k < one_way.size(); ++k) {
    if (std::abs(one_way[k]) > std::abs(one_way[one_way_largest])) one_way_largest = k;
  }
  EXPECT_GT(one_way_largest, 2400u);
}

TEST(BiquadTest, RefusesOddOrdersAndCornersOutsideTheBand) {
  EXPECT_THROW(Butterworth(kRate, 1000.0, false, 3), std::invalid_argument);
  EXPECT_THROW(Butterworth(kRate, 1000.0, false, 0), std::invalid_argument);
  EXPECT_THROW(Butterworth(kRate, 1000.0, false, 18), std::invalid_argument);
  EXPECT_THROW(Butterworth(kRate, 24000.0, true, 4), std::invalid_argument);
  EXPECT_THROW(Butterworth(kRate, 0.0, true, 4), std::invalid_argument);
}

TEST(BiquadTest, APeakingSectionHasItsGainAtItsCentreAndNoneFarFromIt) {
  for (double gain : {-9.0, 6.0}) {
    EXPECT_NEAR(GainDb({PeakingSection(kRate, 2000.0, gain, 2.0)}, 2000.0), gain, 0.2) << gain;
    EXPECT_NEAR(GainDb({PeakingSection(kRate, 2000.0, gain, 2.0)}, 200.0), 0.0, 0.3) << gain;
  }
  EXPECT_THROW(PeakingSection(kRate, 30000.0, 6.0, 1.0), std::invalid_argument);  // beyond Nyquist: unstable
  EXPECT_THROW(PeakingSection(kRate, 2000.0, 6.0, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace nava_modem
