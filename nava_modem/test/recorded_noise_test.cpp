#include "nava_modem/recorded_noise.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
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

TEST(EffectiveSnr, FlatCellsReadAsTheirSnrAndBuriedCellsCostLessThanTheirMeanPower) {
  EXPECT_NEAR(EffectiveSnrDb(std::vector<double>(42, 1.0), -12.0, -11.0), -12.0, 1e-9);
  // Half the cells 2.8 dB louder than the mean and half 10 dB quieter (mean 1).
  const std::vector<double> split = {1.9, 0.1};
  // Well below beta each cell counts by its SNR: the mean of 1/cell, 7.2 dB better than white
  // noise of the same power.
  EXPECT_NEAR(EffectiveSnrDb(split, -40.0, -11.0), -40.0 + 10.0 * std::log10((1.0 / 1.9 + 10.0) / 2.0), 0.05);
  // At beta, better than white noise of its power, worse than all cells as the quiet half.
  const double g = EffectiveSnrDb(split, -11.0, -11.0);
  EXPECT_GT(g, -11.0 + 0.5);
  EXPECT_LT(g, -11.0 + 10.0);
  // Far above beta the buried half holds the code back: the gain is gone.
  EXPECT_LT(EffectiveSnrDb(split, 10.0, -11.0), 10.0);
  EXPECT_THROW(EffectiveSnrDb({}, 0.0, -11.0), std::invalid_argument);
}

// White noise switched on for `on` s and off for `off` s, over `seconds`, at 48 kHz.
std::vector<float> Gated(double on, double off, double seconds, std::uint32_t seed) {
  std::vector<float> x = Floats(WhiteNoise(static_cast<std::size_t>(seconds * 48000.0), seed));
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (std::fmod(k / 48000.0, on + off) >= on) x[k] *= 0.01f;  // 40 dB down, not digital silence
  }
  return x;
}

TEST(RecordingWeight, WhiteNoiseReadsAsTheTablesWhiteNoiseForBothProfiles) {
  const std::vector<float> white = Floats(WhiteNoise(48000 * 8, 11));
  for (Profile p : {Profile::kNava, Profile::kRoom}) {
    const RecordingWeight w(white, 48000.0, p, 48000.0);
    EXPECT_NEAR(w.in_band_offset_db(), 0.0, 0.2);
    for (double snr : {-25.0, -15.0, 0.0}) {
      const std::vector<double> packets = w.TableSnrsDb(snr);
      ASSERT_EQ(packets.size(), p == Profile::kRoom ? RecordingWeight::kPacketWindows : 1u);
      double mean = 0.0;
      for (double t : packets) mean += t / static_cast<double>(packets.size());
      EXPECT_NEAR(mean, snr, 0.5) << ProfileName(p) << " at " << snr << " dB";
    }
  }
}

TEST(RecordingWeight, ANoiseThatComesAndGoesHarmsRoomsCodeLessButNotNavasBits) {
  // On a fifth of the time, in bursts of 0.1 s: 7 dB above its mean while on.
  const std::vector<float> bursts = Gated(0.1, 0.4, 8.0, 5);
  const RecordingWeight room(bursts, 48000.0, Profile::kRoom, 48000.0);
  double mean = 0.0;
  for (double t : room.TableSnrsDb(-15.0)) mean += t / RecordingWeight::kPacketWindows;
  EXPECT_GT(mean, -15.0 + 3.0);
  // Mixed into as much steady noise, it gains less.
  double mixed = 0.0;
  for (double t : room.TableSnrsDb(-15.0, 0.5)) mixed += t / RecordingWeight::kPacketWindows;
  EXPECT_GT(mixed, -15.0);
  EXPECT_LT(mixed, mean);
  // nava decides each 3.3 ms bit alone: a burst on a bit costs the packet, the mean power counts.
  const RecordingWeight nava(bursts, 48000.0, Profile::kNava, 48000.0);
  EXPECT_EQ(nava.TableSnrsDb(-15.0), std::vector<double>{-15.0});
}

TEST(RecordingWeight, ABurstCostsOnlyThePacketsItFallsOn) {
  // Steady white noise with one burst 20 dB louder, 0.3 s long, in 8 s.
  std::vector<float> x = Floats(WhiteNoise(48000 * 8, 9));
  for (std::size_t k = 48000 * 4; k < 48000 * 4 + 14400; ++k) x[k] *= 10.0f;
  const RecordingWeight room(x, 48000.0, Profile::kRoom, 48000.0);
  const std::vector<double> packets = room.TableSnrsDb(-15.0);
  const double power_db = 10.0 * std::log10((8.0 - 0.3 + 0.3 * 100.0) / 8.0);  // the mean over white's
  int clear = 0, hit = 0;
  for (double t : packets) {
    if (t > -15.0 + power_db - 0.5) ++clear;  // as the steady noise alone, 6.7 dB quieter than the mean
    if (t < -15.0 + power_db - 2.0) ++hit;
  }
  EXPECT_GT(clear, static_cast<int>(packets.size()) / 2);
  EXPECT_GT(hit, 0);
}

TEST(RecordingWeight, RoomRefusesARecordingTooSlowForItsBandAndTakesNoSignalAsIs) {
  // At 8 kHz the top of room's 600-5400 Hz band is not in the recording.
  try {
    RecordingWeight(Floats(WhiteNoise(8000 * 4, 2)), 8000.0, Profile::kRoom, 48000.0);
    ADD_FAILURE() << "an 8 kHz recording was weighed for room";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("10800"), std::string::npos) << e.what();
  }
  // nava listens at 2150-3850 Hz, which 8 kHz holds.
  EXPECT_NO_THROW(RecordingWeight(Floats(WhiteNoise(8000 * 4, 2)), 8000.0, Profile::kNava, 48000.0));
  const RecordingWeight room(Floats(WhiteNoise(48000 * 4, 2)), 48000.0, Profile::kRoom, 48000.0);
  for (double t : room.TableSnrsDb(-std::numeric_limits<double>::infinity())) EXPECT_TRUE(std::isinf(t));
}

TEST(CellPowers, RefusesTooShortARecordingOrNoCell) {
  const std::vector<float> white = Floats(WhiteNoise(48000, 3));
  EXPECT_THROW(CellPowers(std::vector<float>(white.begin(), white.begin() + 5000), 48000.0, {{600, 5400}}, 0.04, 400),
               std::invalid_argument);
  EXPECT_THROW(CellPowers(white, 48000.0, {{600, 5400}}, 0.0, 400), std::invalid_argument);
  EXPECT_THROW(CellPowers(white, 48000.0, {{30000, 31000}}, 0.04, 400), std::invalid_argument);
  const auto cells = CellPowers(white, 48000.0, {{600, 5400}}, 0.04, 400);
  ASSERT_EQ(cells.size(), 25u);
  EXPECT_EQ(cells[0].size(), 12u);
}

}  // namespace
}  // namespace nava_modem
