#include "audio_propagation/carrier_share.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "audio_propagation/decode_table.h"

namespace audio_propagation {
namespace {

using nava_modem::Profile;
using world_sim::NoiseKind;

double Share(NoiseKind kind, Profile profile, double whine_hz = 0.0) {
  return CarrierShare(kind, whine_hz, profile, kTableSampleRate);
}

TEST(CarrierShare, WhiteNoiseCountsByItsBandwidth) {
  // nava: two bands of 300 Hz in 24 kHz; room: 600-5400 Hz.
  EXPECT_NEAR(Share(NoiseKind::kWhite, Profile::kNava), 600.0 / 24000.0, 1e-3);
  EXPECT_NEAR(Share(NoiseKind::kWhite, Profile::kRoom), 4800.0 / 24000.0, 1e-3);
}

TEST(CarrierShare, PinkNoiseFallsAsOneOverFrequency) {
  // Density 1/f from 20 Hz, flat below: the share is the bands' log-width over 1 + ln(24000 / 20).
  const double all = 1.0 + std::log(24000.0 / 20.0);
  EXPECT_NEAR(Share(NoiseKind::kPink, Profile::kRoom), std::log(5400.0 / 600.0) / all, 0.02);
  EXPECT_NEAR(Share(NoiseKind::kPink, Profile::kNava),
              (std::log(2450.0 / 2150.0) + std::log(3850.0 / 3550.0)) / all, 0.005);
}

TEST(CarrierShare, AWhineCountsByTheHarmonicsInTheBands) {
  // Harmonics at 1x, 2x, 3x with powers 1, 1/4, 1/16. A 400 Hz compressor: room hears 800 and
  // 1200 Hz, a quarter of it; nava none.
  EXPECT_NEAR(Share(NoiseKind::kWhine, Profile::kRoom, 400.0), (0.25 + 0.0625) / 1.3125, 0.03);
  EXPECT_LT(Share(NoiseKind::kWhine, Profile::kNava, 400.0), 0.01);
  // On nava's mark: the fundamental, most of it.
  EXPECT_NEAR(Share(NoiseKind::kWhine, Profile::kNava, 2300.0), 1.0 / 1.3125, 0.05);
}

TEST(CarrierShare, SpeechLiesMostlyBelowTheBands) {
  EXPECT_LT(Share(NoiseKind::kSpeech, Profile::kNava), 0.05);
  EXPECT_GT(Share(NoiseKind::kSpeech, Profile::kRoom), 0.2);
  EXPECT_LT(Share(NoiseKind::kSpeech, Profile::kRoom), 0.7);
}

TEST(CarrierShare, ARecordingOrAnImpossibleWhineIsRefused) {
  EXPECT_THROW(Share(NoiseKind::kRecording, Profile::kRoom), std::invalid_argument);
  EXPECT_THROW(Share(NoiseKind::kWhine, Profile::kRoom, 0.0), std::invalid_argument);
  EXPECT_THROW(Share(NoiseKind::kWhine, Profile::kRoom, 30000.0), std::invalid_argument);
}

}  // namespace
}  // namespace audio_propagation
