// The direction estimator's stages alone: the band layout, the Welch analysis and one pair's
// GCC-PHAT, on signals whose answer is known.
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <gtest/gtest.h>

#include "array_signals.h"
#include "nava_modem/band_spectra.h"
#include "nava_modem/gcc_phat.h"

namespace nava_modem {
namespace {

using namespace array_signals;

TEST(BandLayout, SegmentsOf20MsAndTheBandsBins) {
  const BandLayout a = BandLayoutFor(48000.0, 500.0, 6000.0, 0.2 / 343.0);
  EXPECT_EQ(a.segment, 1024u);  // 960 samples, to a power of two
  EXPECT_DOUBLE_EQ(a.bin_hz, 46.875);
  EXPECT_EQ(a.low_bin, 11u);    // the first bin at or above 500 Hz
  EXPECT_EQ(a.high_bin, 128u);  // the last at or below 6000 Hz
  EXPECT_EQ(BandLayoutFor(16000.0, 500.0, 6000.0, 0.2 / 343.0).segment, 512u);
  // A wide array: 8 times its largest delay.
  EXPECT_EQ(BandLayoutFor(48000.0, 500.0, 6000.0, 0.01).segment, 4096u);
  // Never bin 0, never past Nyquist.
  const BandLayout whole = BandLayoutFor(16000.0, 0.0, 8000.0, 0.001);
  EXPECT_EQ(whole.low_bin, 1u);
  EXPECT_EQ(whole.high_bin, whole.segment / 2);
}

TEST(WelchAnalyser, CutsEachChannelIntoAtMostEightSegments) {
  const BandLayout layout = BandLayoutFor(48000.0, 500.0, 6000.0, 0.001);
  const WelchAnalyser welch(layout, 9600);
  const std::vector<float> x = BandNoise(20000, 48000.0, 500.0, 6000.0, 1);
  EXPECT_EQ(welch.Analyse({x.data()}, 300).segments, 1u);   // shorter than a segment
  EXPECT_EQ(welch.Analyse({x.data()}, 1024).segments, 1u);
  EXPECT_EQ(welch.Analyse({x.data()}, 3000).segments, 3u);  // back to back
  EXPECT_EQ(welch.Analyse({x.data()}, 20000).segments, 8u); // spread over the first 9600
  EXPECT_EQ(welch.Analyse({x.data()}, 0).segments, 0u);
  const BandSpectra s = welch.Analyse({x.data(), x.data()}, 3000);
  EXPECT_EQ(s.bins, layout.high_bin - layout.low_bin + 1);
  ASSERT_EQ(s.channel.size(), 2u);
  EXPECT_EQ(s.channel[0].size(), s.segments * s.bins);
  EXPECT_EQ(s.channel[0], s.channel[1]);
  // The power is the segments' squared magnitudes summed.
  for (std::size_t b = 0; b < s.bins; b += 17) {
    double sum = 0.0;
    for (std::size_t g = 0; g < s.segments; ++g) sum += std::norm(s.channel[0][g * s.bins + b]);
    EXPECT_NEAR(s.power[0][b], sum, 1e-9 * sum);
  }
  // Only the first max_samples count: what follows them changes nothing.
  std::vector<float> changed = x;
  std::fill(changed.begin() + 9600, changed.end(), 0.0f);
  EXPECT_EQ(welch.Analyse({changed.data()}, 20000).channel, welch.Analyse({x.data()}, 20000).channel);
}

TEST(WelchAnalyser, ATonesPowerLiesInItsBin) {
  const BandLayout layout = BandLayoutFor(48000.0, 500.0, 6000.0, 0.001);
  const WelchAnalyser welch(layout, 9600);
  const std::size_t bin = 50;  // 2343.75 Hz
  std::vector<float> tone(9600);
  for (std::size_t k = 0; k < tone.size(); ++k) tone[k] = static_cast<float>(std::sin(2.0 * M_PI * bin * layout.bin_hz * k / 48000.0));
  const BandSpectra s = welch.Analyse({tone.data()}, tone.size());
  const auto strongest = std::max_element(s.power[0].begin(), s.power[0].end()) - s.power[0].begin();
  EXPECT_EQ(static_cast<std::size_t>(strongest) + layout.low_bin, bin);
  // The window's tapers keep it from leaking far: 10 bins off, 30 dB under.
  EXPECT_LT(s.power[0][bin - layout.low_bin + 10], 1e-3 * s.power[0][bin - layout.low_bin]);
}

TEST(GccPhat, PeaksAtThePairsDelay) {
  const double rate = 48000.0, max_delay = 0.2 / 343.0;  // 28 samples
  const BandLayout layout = BandLayoutFor(rate, 500.0, 6000.0, max_delay);
  const WelchAnalyser welch(layout, 9600);
  const GccPhat gcc(layout, rate, 6000.0, max_delay);
  EXPECT_EQ(gcc.interpolation(), 1u);  // 8 x 6 kHz within 48 kHz
  EXPECT_EQ(GccPhat(layout, 16000.0, 6000.0, max_delay).interpolation(), 4u);
  const std::vector<float> source = BandNoise(9600, rate, 500.0, 6000.0, 2);
  for (double delay : {0.0, 5.0, -12.0}) {
    const std::vector<float> i = Delayed(source, 40.0), j = Delayed(source, 40.0 + delay);
    const PairCorrelation r = gcc.Correlate(welch.Analyse({i.data(), j.data()}, i.size()), 0, 1);
    EXPECT_EQ(r.half, 30);  // 27.99 samples and 2 more, up
    ASSERT_EQ(r.lags.size(), 61u);
    EXPECT_GT(r.used, 0u);
    const auto best = std::max_element(r.lags.begin(), r.lags.end()) - r.lags.begin();
    EXPECT_EQ(best - r.half, static_cast<std::ptrdiff_t>(delay)) << delay;
    EXPECT_NEAR(r.lags[static_cast<std::size_t>(best)], 1.0, 0.05) << delay;  // a clean delay
    EXPECT_NEAR(r.At(delay), r.lags[static_cast<std::size_t>(best)], 1e-12);
    // All of the cross-power lines up at one delay: its size is nearly the most it could be
    // (the segments' edges cut the two channels a few samples apart).
    double size = 0.0;
    for (const auto& c : r.cross) size += std::abs(c);
    EXPECT_NEAR(size, r.power, 1e-2 * r.power);
  }
  // Silence: no bin in the sum, no correlation.
  const std::vector<float> silence(9600, 0.0f);
  const PairCorrelation none = gcc.Correlate(welch.Analyse({silence.data(), silence.data()}, silence.size()), 0, 1);
  EXPECT_EQ(none.used, 0u);
  EXPECT_TRUE(std::all_of(none.lags.begin(), none.lags.end(), [](double v) { return v == 0.0; }));
}

TEST(PairCorrelation, ReadsBetweenLagsAndClampsAtTheEnds) {
  PairCorrelation r;
  r.half = 2;
  r.lags = {0.0, 1.0, 3.0, 2.0, 0.0};  // lags -2..2
  EXPECT_DOUBLE_EQ(r.At(0.0), 3.0);
  EXPECT_DOUBLE_EQ(r.At(-0.5), 2.0);
  EXPECT_DOUBLE_EQ(r.At(0.25), 2.75);
  EXPECT_DOUBLE_EQ(r.At(2.0), 0.0);
  EXPECT_DOUBLE_EQ(r.At(-7.0), 0.0);
  EXPECT_DOUBLE_EQ(r.At(1.5), 1.0);
}

}  // namespace
}  // namespace nava_modem
