// Measured impulse responses: reading one channel of a file (resampled, its delay kept), the
// refusals that name the file, the figures (RT60 and DRR in 600-5400 Hz) on responses whose
// figures are known, and rendering through one.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "known_response.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"

namespace nava_modem {
namespace {

std::string TempPath(const std::string& name) { return ::testing::TempDir() + "/measured_response_" + name; }

TEST(MeasuredResponseTest, FiguresOfResponsesWhoseFiguresAreKnown) {
  for (double rate : {44100.0, 48000.0}) {
    for (double rt60 : {0.3, 0.8, 2.0}) {
      for (double drr : {-10.0, 0.0, 8.0}) {
        const std::size_t delay = static_cast<std::size_t>(0.02 * rate);
        const ResponseMeasures m = MeasureResponse(KnownResponse(rt60, drr, rate, delay, 3), rate);
        EXPECT_EQ(m.peak, delay) << rate << " " << rt60 << " " << drr;
        // The 5 ms before the tail, flat in Schroeder's curve, lengthen a short T30 a little
        // where the direct sound is strong.
        EXPECT_NEAR(m.rt60_s, rt60, 0.05 * rt60 + 0.01) << rate << " " << rt60 << " " << drr;
        EXPECT_NEAR(m.drr_db, drr, 0.5) << rate << " " << rt60 << " " << drr;
      }
    }
  }
}

// A file cut at its direct sound (and every response the renderer makes) starts with it: the
// band's zero-phase filters spread the direct pulse both ways, and the half before the file's
// start was lost, reading the DRR 3 dB low.
TEST(MeasuredResponseTest, AResponseThatStartsWithItsDirectSoundReadsAsOneWithSilenceBefore) {
  for (double drr : {-6.0, 0.0, 6.0}) {
    const ResponseMeasures at_start = MeasureResponse(KnownResponse(0.6, drr, 48000.0, 0, 5), 48000.0);
    const ResponseMeasures delayed = MeasureResponse(KnownResponse(0.6, drr, 48000.0, 960, 5), 48000.0);
    EXPECT_EQ(at_start.peak, 0u);
    EXPECT_NEAR(at_start.drr_db, drr, 0.5) << drr;
    EXPECT_NEAR(at_start.drr_db, delayed.drr_db, 0.05) << drr;
    EXPECT_NEAR(at_start.rt60_s, delayed.rt60_s, 0.01) << drr;
    EXPECT_EQ(at_start.before_db, -std::numeric_limits<double>::infinity());
  }
}

TEST(MeasuredResponseTest, AResponseWithNothingAfterItsDirectSoundHasAnInfiniteDrr) {
  std::vector<float> h(4800, 0.0f);
  h[100] = 0.5f;
  const ResponseMeasures m = MeasureResponse(h, 48000.0);
  EXPECT_EQ(m.peak, 100u);
  EXPECT_GT(m.drr_db, 20.0);  // the band-pass's ringing is all that follows
  EXPECT_THROW(MeasureResponse(std::vector<float>(4800, 0.0f), 48000.0), std::invalid_argument);
  EXPECT_THROW(MeasureResponse({}, 48000.0), std::invalid_argument);
  EXPECT_THROW(MeasureResponse(h, 8000.0), std::invalid_argument);
}

TEST(MeasuredResponseTest, ADrierResponseReadsTheDrrAskedForAndKeepsItsDecayAndDirectSound) {
  const double rate = 48000.0;
  const std::vector<float> room = KnownResponse(0.8, -6.0, rate, 960, 7);
  const ResponseMeasures own = MeasureResponse(room, rate);
  for (double drr : {own.drr_db, 4.0, 12.0}) {
    const std::vector<float> drier = DrierResponse(room, rate, drr);
    const ResponseMeasures m = MeasureResponse(drier, rate);
    EXPECT_NEAR(m.drr_db, drr, 0.01);
    EXPECT_NEAR(m.rt60_s, own.rt60_s, 0.05 * own.rt60_s) << drr;
    EXPECT_EQ(m.peak, own.peak);
    EXPECT_EQ(drier[960], room[960]);  // the direct sound as it was
  }
  // It makes rooms drier only.
  EXPECT_THROW(DrierResponse(room, rate, own.drr_db - 1.0), std::invalid_argument);
  EXPECT_THROW(DrierResponse(room, rate, std::nan("")), std::invalid_argument);
  // Drier than the direct sound alone reads (the band's filters spread it past 2.5 ms): refused.
  EXPECT_THROW(DrierResponse(room, rate, 200.0), std::invalid_argument);
}

TEST(MeasuredResponseTest, ARoomsResponseServesAndShortOrNoisyOnesAreToldWhy) {
  const double rate = 48000.0;
  const ResponseMeasures room = MeasureResponse(KnownResponse(0.5, 0.0, rate, 960, 4), rate);
  EXPECT_LT(room.before_db, -40.0);  // only the band-pass's ringing before the direct sound
  EXPECT_NEAR(room.after_s, 0.75 - 0.0025, 0.001);
  EXPECT_FALSE(ResponseProblem(room).has_value());
  // Cut 20 ms after its direct sound.
  std::vector<float> cut = KnownResponse(0.5, 0.0, rate, 960, 4);
  cut.resize(960 + 960);
  const auto short_one = ResponseProblem(MeasureResponse(cut, rate));
  ASSERT_TRUE(short_one.has_value());
  EXPECT_NE(short_one->find("too short"), std::string::npos) << *short_one;
  // Noise: its largest sample has far more sound before it than within 2.5 ms of it.
  std::mt19937 rng(5);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<float> noise(48000);
  for (float& v : noise) v = static_cast<float>(gauss(rng));
  const ResponseMeasures heard = MeasureResponse(noise, rate);
  const auto no_peak = ResponseProblem(heard);
  ASSERT_TRUE(no_peak.has_value());
  EXPECT_NE(no_peak->find("no direct peak"), std::string::npos) << *no_peak;
  EXPECT_GT(heard.before_db, kMaxBeforeDb);
  // A room heard behind an obstacle: its loudest arrival 20 ms after sixteen weaker ones (each
  // 4.4 dB under it) that together hold some 7 dB more sound than it does (an empty bedroom's
  // far ear holds 5.6 dB).
  std::vector<float> behind = KnownResponse(0.5, 0.0, rate, 1920, 4);
  const float direct = behind[1920];
  for (std::size_t k = 0; k < 16; ++k) behind[960 + 57 * k] += 0.6f * direct;
  const ResponseMeasures heard_behind = MeasureResponse(behind, rate);
  EXPECT_EQ(heard_behind.peak, 1920u);
  EXPECT_GT(heard_behind.before_db, 6.0);
  EXPECT_FALSE(ResponseProblem(heard_behind).has_value()) << *ResponseProblem(heard_behind);
}

// A response carrying noise of its own (as one estimated from packets does): white noise whose
// power per sample is `floor_db` under the response's reverberation at its start, over the
// response and 3 s past its end.
struct NoisyResponse {
  std::vector<float> clean, noisy;
  double noise_power = 0.0;  // in 600-5400 Hz, as MeasureResponseOverNoise takes it
};
NoisyResponse WithNoise(const std::vector<float>& clean, double rate, double floor_db, unsigned seed) {
  NoisyResponse r;
  r.clean = clean;
  r.clean.resize(clean.size() + static_cast<std::size_t>(3.0 * rate), 0.0f);
  double early = 0.0;  // mean energy over the 50 ms after the direct sound
  const std::size_t peak = static_cast<std::size_t>(std::max_element(clean.begin(), clean.end()) - clean.begin());
  const std::size_t span = static_cast<std::size_t>(0.05 * rate);
  for (std::size_t k = peak + 1; k <= peak + span; ++k) early += clean[k] * clean[k] / static_cast<double>(span);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, std::sqrt(early * std::pow(10.0, -floor_db / 10.0)));
  std::vector<float> noise(r.clean.size());
  for (float& v : noise) v = static_cast<float>(gauss(rng));
  r.noisy = r.clean;
  for (std::size_t k = 0; k < noise.size(); ++k) r.noisy[k] += noise[k];
  r.noise_power = InBandPower(noise, rate);
  return r;
}

TEST(MeasuredResponseTest, OverItsNoiseFloorAResponseGivesTheFiguresItWouldGiveWithout) {
  constexpr double kRate = 48000.0;
  for (double rt60 : {0.5, 1.7}) {
    for (double drr : {-8.0, 2.0}) {
      // The decay stands 25 dB above the floor: short of the 35 dB that T30 reads.
      const NoisyResponse r = WithNoise(KnownResponse(rt60, drr, kRate, 960, 5), kRate, 25.0, 9);
      const ResponseMeasures truth = MeasureResponse(r.clean, kRate);
      const ResponseMeasures m = MeasureResponseOverNoise(r.noisy, r.noise_power, kRate);
      EXPECT_NEAR(m.rt60_s, truth.rt60_s, 0.1 * truth.rt60_s) << rt60 << " " << drr;
      EXPECT_NEAR(m.drr_db, truth.drr_db, 1.0) << rt60 << " " << drr;
      EXPECT_EQ(m.peak, truth.peak);
      // Read as if the noise were the room, the decay comes out far too long.
      EXPECT_GT(MeasureResponse(r.noisy, kRate).rt60_s, 1.3 * truth.rt60_s) << rt60 << " " << drr;
    }
  }
}

TEST(MeasuredResponseTest, WithoutNoiseTheFiguresOverNoiseAreTheFigures) {
  const std::vector<float> h = KnownResponse(0.8, -3.0, 48000.0, 480, 2);
  const ResponseMeasures a = MeasureResponse(h, 48000.0), b = MeasureResponseOverNoise(h, 0.0, 48000.0);
  EXPECT_EQ(a.peak, b.peak);
  EXPECT_DOUBLE_EQ(a.rt60_s, b.rt60_s);
  EXPECT_DOUBLE_EQ(a.drr_db, b.drr_db);
  EXPECT_DOUBLE_EQ(a.after_s, b.after_s);
  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(MeasureResponseOverNoise(h, bad, 48000.0), std::invalid_argument) << bad;
  }
}

TEST(MeasuredResponseTest, LoadsTheChannelAskedForResampledWithItsDelayKept) {
  const double rate = 44100.0;
  const std::vector<float> left = KnownResponse(0.5, 3.0, rate, 441, 1);  // direct sound at 10 ms
  std::vector<float> right(left.size(), 0.0f);
  right[882] = 0.8f;  // at 20 ms
  const std::string path = TempPath("stereo.wav");
  WriteFloatWavFile(TempPath("mono.wav"), left, rate);
  WriteWavChannels(path, {left, right}, rate);

  const std::vector<float> mono = LoadImpulseResponse(TempPath("mono.wav"), std::nullopt, rate);
  ASSERT_EQ(mono.size(), left.size());
  EXPECT_FLOAT_EQ(mono[441], 1.0f);
  const std::vector<float> r48 = LoadImpulseResponse(path, 1, 48000.0);
  EXPECT_NEAR(static_cast<double>(r48.size()), left.size() * 48000.0 / rate, 20.0);
  EXPECT_EQ(MeasureResponse(r48, 48000.0).peak, 960u);  // 20 ms at 48 kHz
  EXPECT_EQ(MeasureResponse(LoadImpulseResponse(path, 0, 48000.0), 48000.0).peak, 480u);
}

// Every refusal is one line that names the file and says what was expected.
void ExpectRefusal(const std::string& path, std::optional<int> channel, const std::string& says) {
  try {
    LoadImpulseResponse(path, channel, 48000.0);
    ADD_FAILURE() << path << ": accepted";
  } catch (const ResponseFileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(says), std::string::npos) << what;
    EXPECT_NE(what.find("expected"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(MeasuredResponseTest, RefusesUnreadableSilentAndAmbiguousFilesNamingThem) {
  const std::string stereo = TempPath("refuse_stereo.wav"), silent = TempPath("silent.wav"), text = TempPath("text.wav");
  std::vector<float> h(1000, 0.0f);
  h[10] = 1.0f;
  WriteWavChannels(stereo, {h, h}, 48000.0);
  WriteWavFile(silent, std::vector<float>(1000, 0.0f), 48000.0);
  std::FILE* f = std::fopen(text.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("not audio\n", f);
  std::fclose(f);
  ExpectRefusal(stereo, std::nullopt, "2 channels");
  ExpectRefusal(stereo, 2, "channel 2");
  ExpectRefusal(silent, std::nullopt, "silent");
  ExpectRefusal(text, std::nullopt, text);
  ExpectRefusal(TempPath("missing.wav"), std::nullopt, "missing.wav");
}

TEST(MeasuredResponseTest, RenderingThroughAResponseKeepsItsDelayAndSetsTheSnrWhereThePacketIsHeard) {
  const double rate = 48000.0;
  std::vector<float> clean(static_cast<std::size_t>(0.5 * rate), 0.0f);
  for (std::size_t k = 4800; k < 14400; ++k) clean[k] = static_cast<float>(0.5 * std::sin(6.283185307 * 3000.0 * k / rate));
  RoomOptions o;
  o.response.assign(static_cast<std::size_t>(0.2 * rate), 0.0f);
  o.response[static_cast<std::size_t>(0.1 * rate)] = 1.0f;  // a pure delay of 100 ms
  RoomRenderInfo info;
  const std::vector<float> heard = RenderRoom(clean, rate, o, {}, &info);
  ASSERT_EQ(heard.size(), clean.size() + o.response.size() - 1);
  EXPECT_NEAR(heard[4800 + 4800 + 100], 0.9f * std::sin(6.283185307 * 3000.0 * (4800 + 100) / rate), 1e-3);
  EXPECT_NEAR(std::abs(heard[4800 + 10]), 0.0, 1e-6);  // before the delay: silence
  // The level the SNR refers to is the tone's (0.125, a little less with the sounding window's
  // edges), where the delayed tone sounds: not counted where it is not yet heard (0.06).
  EXPECT_NEAR(info.signal_power, 0.125, 0.01);

  RoomOptions both = o;
  both.rt60 = 0.5;
  EXPECT_THROW(RenderRoom(clean, rate, both), RoomOptionError);
  RoomOptions silent;
  silent.response.assign(100, 0.0f);
  EXPECT_THROW(RenderRoom(clean, rate, silent), RoomOptionError);
}

}  // namespace
}  // namespace nava_modem
