#include "nava_modem/recorded_noise.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/noise_sources.h"

namespace nava_modem {
namespace {

std::vector<float> Floats(const std::vector<double>& x) { return std::vector<float>(x.begin(), x.end()); }

std::vector<float> Tone(double hz, double rate, std::size_t n) {
  std::vector<float> x(n);
  for (std::size_t k = 0; k < n; ++k) x[k] = static_cast<float>(0.3 * std::sin(2.0 * std::acos(-1.0) * hz * k / rate));
  return x;
}

TEST(ListeningBands, NavaListensAtItsTwoTonesAndRoomOverItsBand) {
  const Bands nava = ListeningBands(Profile::kNava);
  ASSERT_EQ(nava.size(), 2u);
  EXPECT_DOUBLE_EQ(nava[0].first, 2150.0);
  EXPECT_DOUBLE_EQ(nava[0].second, 2450.0);
  EXPECT_DOUBLE_EQ(nava[1].first, 3550.0);
  const Bands room = ListeningBands(Profile::kRoom);
  ASSERT_EQ(room.size(), 1u);
  EXPECT_DOUBLE_EQ(room[0].first, 600.0);
  EXPECT_DOUBLE_EQ(room[0].second, 5400.0);
  EXPECT_NEAR(WhiteFraction(room, 48000.0), 0.2, 1e-12);
}

TEST(RecordedNoise, WhiteNoiseReadsAsWhiteNoise) {
  const RecordedNoise white(Floats(WhiteNoise(48000 * 4, 7)), 48000.0);
  EXPECT_NEAR(white.power(), 1.0, 0.02);
  for (Profile p : {Profile::kNava, Profile::kRoom}) {
    EXPECT_NEAR(white.Fraction(ListeningBands(p)), WhiteFraction(ListeningBands(p), 48000.0), 0.002);
    EXPECT_NEAR(WhiteEquivalentOffsetDb(white, ListeningBands(p), 48000.0), 0.0, 0.2);
  }
}

TEST(RecordedNoise, WhiteNoiseSampledSlowerPutsMoreOfItsPowerInTheBand) {
  // At 16 kHz the same full-band power spreads over a third of the spectrum: three times (4.8 dB)
  // more of it in any band the two rates share.
  const RecordedNoise white(Floats(WhiteNoise(16000 * 4, 3)), 16000.0);
  EXPECT_NEAR(WhiteEquivalentOffsetDb(white, ListeningBands(Profile::kNava), 48000.0), -4.77, 0.3);
}

TEST(RecordedNoise, PinkNoiseReadsAsItsSlopeSaysAndAToneOnOneOfNavasHitsItHard) {
  const Bands nava = ListeningBands(Profile::kNava);
  // 1/f from 20 Hz up, flat below: of a total of 1 + ln(24000 / 20), ln(hi / lo) per band.
  const RecordedNoise pink(Floats(PinkNoise(48000 * 8, 48000.0, 5)), 48000.0);
  const double total = 1.0 + std::log(24000.0 / 20.0);
  const double in_nava = (std::log(2450.0 / 2150.0) + std::log(3850.0 / 3550.0)) / total;
  EXPECT_NEAR(WhiteEquivalentOffsetDb(pink, nava, 48000.0), 10.0 * std::log10(0.025 / in_nava), 0.3);
  const double in_room = std::log(5400.0 / 600.0) / total;
  EXPECT_NEAR(WhiteEquivalentOffsetDb(pink, ListeningBands(Profile::kRoom), 48000.0), 10.0 * std::log10(0.2 / in_room),
              0.3);
  const RecordedNoise on_mark(Tone(2300.0, 48000.0, 48000), 48000.0);
  EXPECT_NEAR(on_mark.Fraction(nava), 1.0, 0.01);
  EXPECT_NEAR(WhiteEquivalentOffsetDb(on_mark, nava, 48000.0), 10.0 * std::log10(600.0 / 24000.0), 0.1);
  // Between the tones it is nearly harmless to nava and all of it is in the room profile's band.
  const RecordedNoise between(Tone(3000.0, 48000.0, 48000), 48000.0);
  EXPECT_LT(between.Fraction(nava), 0.001);
  EXPECT_NEAR(between.Fraction(ListeningBands(Profile::kRoom)), 1.0, 0.001);
}

TEST(RecordedNoise, RefusesWhatIsNoRecording) {
  EXPECT_THROW(RecordedNoise(std::vector<float>(100, 0.1f), 48000.0), std::invalid_argument);
  EXPECT_THROW(RecordedNoise(std::vector<float>(10000, 0.0f), 48000.0), std::invalid_argument);
  EXPECT_THROW(RecordedNoise(std::vector<float>(10000, 0.1f), 0.0), std::invalid_argument);
  std::vector<float> bad(10000, 0.1f);
  bad[5000] = std::numeric_limits<float>::quiet_NaN();
  try {
    RecordedNoise noise(bad, 48000.0);
    ADD_FAILURE() << "a NaN sample was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nava_modem
