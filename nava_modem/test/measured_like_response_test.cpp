// Room responses like measured ones (measured_like_response.h), held against the figures they are
// asked for and against the rooms of ../shared/realrooms (when that folder is beside the project).
#include "nava_modem/measured_like_response.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "known_response.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/real_fft.h"
#include "nava_modem/response_features.h"
#include "nava_modem/room_impulse_response.h"
#include "nava_modem/wav_file.h"

namespace nava_modem {
namespace {

constexpr double kRate = 48000.0;

TEST(MeasuredLikeResponseTest, ReadsTheAskedRt60AndDrr) {
  for (double rt60 : {0.3, 2.4}) {
    for (double drr : {-24.0, -6.0, 0.0, 12.0}) {
      const std::vector<float> h = MeasuredLikeResponse(rt60, drr, kRate, 3);
      const ResponseMeasures m = MeasureResponse(h, kRate);
      EXPECT_NEAR(m.rt60_s, rt60, 0.05 * rt60) << rt60 << " s, " << drr << " dB";
      if (drr >= -6.0) {
        EXPECT_NEAR(m.drr_db, drr, 0.3) << rt60 << " s, " << drr << " dB";
      } else {
        // Read about the reverberation's largest peak: higher than the room's, still reverberant.
        EXPECT_GE(m.drr_db, drr - 0.3) << rt60 << " s, " << drr << " dB";
        EXPECT_LT(m.drr_db, -3.0) << rt60 << " s, " << drr << " dB";
      }
      // The largest peak, where the definition reads the direct sound, is the direct sound's or
      // the floor's just after it (far below DRR 0 it can be the reverberation's).
      if (drr >= -6.0) {
        EXPECT_NEAR(static_cast<double>(m.peak), static_cast<double>(kMeasuredLikeDelay), kDirectHalfWidthS * kRate)
            << rt60 << " " << drr;
      }
      EXPECT_EQ(h.size(), kMeasuredLikeDelay + RoomResponseSamples(rt60, kRate));
    }
  }
}

// At a low sample rate the resonances stay below Nyquist (a section above it would be unstable).
TEST(MeasuredLikeResponseTest, AtALowSampleRateTheResponseIsFinite) {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const std::vector<float> h = MeasuredLikeResponse(0.4, 0.0, 11025.0, seed);
    ASSERT_TRUE(std::all_of(h.begin(), h.end(), [](float v) { return std::isfinite(v); })) << seed;
    EXPECT_NEAR(MeasureResponse(h, 11025.0).drr_db, 0.0, 0.3) << seed;
  }
}

TEST(MeasuredLikeResponseTest, SameSeedSameRoomOtherSeedOtherRoom) {
  EXPECT_EQ(MeasuredLikeResponse(0.5, 0.0, kRate, 7), MeasuredLikeResponse(0.5, 0.0, kRate, 7));
  EXPECT_NE(MeasuredLikeResponse(0.5, 0.0, kRate, 7), MeasuredLikeResponse(0.5, 0.0, kRate, 8));
}

TEST(MeasuredLikeResponseTest, RefusesArgumentsOutOfRangeNamingThem) {
  const auto refused = [](auto call, const std::string& words) {
    try {
      call();
      ADD_FAILURE() << "accepted: expected '" << words << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused([] { MeasuredLikeResponse(0.0, 0.0, kRate, 1); }, "rt60");
  refused([] { MeasuredLikeResponse(11.0, 0.0, kRate, 1); }, "rt60");
  refused([] { MeasuredLikeResponse(0.5, 41.0, kRate, 1); }, "drr_db");
  refused([] { MeasuredLikeResponse(0.5, 0.0, 8000.0, 1); }, "sample rate");
  refused([] { MeasuredLikeResponse(0.5, 0.0, kRate, 1, ResponseGeometry{-1.0, 0.0, 0.0, 0.0}); }, "distance_m");
  refused([] { MeasuredLikeResponse(0.5, 0.0, kRate, 1, ResponseGeometry{2.0, 3.0, 0.3, 2.5}); }, "source_height_m");
  refused([] { MeasuredLikeResponse(0.5, 0.0, kRate, 1, ResponseGeometry{0.2, 0.5, 0.2, 2.5}); }, "distance_m");
}

// The level (dB) at `hz` of x's first `length` samples, flat for their first two thirds (the
// direct sound and the floor's reflection weighed alike) and tapered over the last third.
double LevelAt(const std::vector<float>& x, std::size_t length, double hz) {
  std::complex<double> sum(0.0, 0.0);
  const double flat = 2.0 * static_cast<double>(length) / 3.0, taper = static_cast<double>(length) - flat;
  for (std::size_t k = 0; k < length; ++k) {
    const double t = static_cast<double>(k);
    const double w = t < flat ? 1.0 : 0.5 + 0.5 * std::cos(M_PI * (t - flat) / taper);
    sum += w * static_cast<double>(x[k]) * std::polar(1.0, -2.0 * M_PI * hz * static_cast<double>(k) / kRate);
  }
  return 20.0 * std::log10(std::abs(sum) + 1e-30);
}

// A loudspeaker and a microphone 0.5 m above the floor, 1 m apart: the floor's reflection comes
// 1.2 ms after the direct sound (0.41 m further) and cuts notches at odd multiples of 414 Hz. The
// same room (same seed) with both 5 cm above the floor has its floor's reflection on the direct
// sound: the ratio of the two direct sounds' spectra is the comb alone.
TEST(MeasuredLikeResponseTest, TheFloorsReflectionFollowsTheGeometry) {
  const ResponseGeometry high{1.0, 0.5, 0.5, 3.0}, low{1.0, 0.05, 0.05, 3.0};
  const double delay_s = (std::sqrt(1.0 + 1.0) - 1.0) / 343.0;
  double peaks = 0.0, notches = 0.0;
  int counted = 0;
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const std::vector<float> a = MeasuredLikeResponse(0.6, 6.0, kRate, seed, high);
    const std::vector<float> b = MeasuredLikeResponse(0.6, 6.0, kRate, seed, low);
    const std::size_t window = static_cast<std::size_t>(0.006 * kRate);
    for (int m = 2; m <= 5; ++m) {
      const double peak_hz = m / delay_s, notch_hz = (m + 0.5) / delay_s;
      if (notch_hz > kResponseBandHighHz) break;
      peaks += LevelAt(a, window, peak_hz) - LevelAt(b, window, peak_hz);
      notches += LevelAt(a, window, notch_hz) - LevelAt(b, window, notch_hz);
      ++counted;
    }
  }
  ASSERT_GT(counted, 0);
  EXPECT_GT((peaks - notches) / counted, 6.0) << "peaks " << peaks / counted << " dB, notches " << notches / counted;
}

// The median of the finite values (a decay ratio is NaN where an octave gives no RT60).
double Median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Range {
  double low = 1e300, high = -1e300;
  void Add(double v) { low = std::min(low, v), high = std::max(high, v); }
};

// onset_db: the share of the reverberation within kOnsetEndS of the direct sound. A tail that
// starts 5 ms after it and decays by 60 dB in T holds 1 - exp(-13.8 x 5 ms / T) of its energy in
// 5-10 ms: -5.4 dB for T = 0.2 s, -14.7 dB for 2 s, whatever the DRR.
TEST(ResponseFeaturesTest, OnsetIsTheReverberationsShareInItsFirstMilliseconds) {
  const auto expected = [](double rt60) { return 10.0 * std::log10(1.0 - std::exp(-13.8155 * 0.005 / rt60)); };
  for (const double rt60 : {0.2, 2.0}) {
    for (const double drr : {-10.0, 6.0}) {
      const ResponseFeatures f = MeasureFeatures(KnownResponse(rt60, drr, kRate, 480, 3), kRate, 2300.0, 3700.0);
      EXPECT_NEAR(f.onset_db, expected(rt60), 1.0) << "RT60 " << rt60 << " s, DRR " << drr << " dB";
    }
  }
}

// reverb_edt_ratio: one exponential decays from its start as it does over -5..-35 dB (1; the
// first 10 dB of a short decay are few cycles of noise, so a single tail reads 0.9-1.2 and the
// mean of six is held). A tail whose first decay (0.3 s) falls 15 dB under a slower one (1.5 s)
// decays at 0.47 s from its start, while its T30 reads the slow decay: 1.43 s, a ratio of 0.33
// (worked out from the envelopes; the direct sound in the T30's curve makes it about 0.39).
TEST(ResponseFeaturesTest, ReverbEarlyDecayRatioTellsAFastFirstDecay) {
  for (const double rt60 : {0.3, 2.0}) {
    for (const double drr : {-10.0, 6.0}) {
      double mean = 0.0;
      for (unsigned seed = 1; seed <= 6; ++seed) {
        mean += MeasureFeatures(KnownResponse(rt60, drr, kRate, 480, seed), kRate, 2300.0, 3700.0).reverb_edt_ratio / 6.0;
      }
      EXPECT_NEAR(mean, 1.0, 0.07) << "RT60 " << rt60 << " s, DRR " << drr << " dB";
    }
  }
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const ResponseFeatures f = MeasureFeatures(KnownResponse(0.3, -10.0, kRate, 480, seed, 1.5, -15.0), kRate, 2300.0, 3700.0);
    EXPECT_NEAR(f.reverb_edt_ratio, 0.39, 0.07) << "seed " << seed;
  }
}

// What measured rooms hold and the statistical response lacks (measured_like_response.h): the
// medians of the new responses' features lie within what the measured rooms show; the statistical
// response's colouring lies below it.
TEST(MeasuredLikeResponseTest, ItsFeaturesLieWhereMeasuredRoomsLie) {
  const std::filesystem::path rooms = MULTIROBOT_AUDIO_REALROOMS;
  // Six of the 14 files (for time), which between them reach nearly the whole range all 27
  // room-ears show of each feature (the teaching room from -80 degrees: the least coloured
  // direct sound, 3.8 dB, and the least coloured response, 2.7 dB).
  const char* files[] = {"rir_clap.wav", "brir_sweep_Netzwerkakademie_headaz+40.wav",
                         "brir_sweep_Netzwerkakademie_headaz-80.wav", "pori_s1_r1_b.wav", "pori_s2_r2_b.wav",
                         "museum_basement_clap.wav"};
  for (const char* file : files) {
    if (!std::filesystem::exists(rooms / file)) GTEST_SKIP() << "no " << file << " in " << rooms;
  }
  Range colour, direct_colour, tone, decay, spread;
  for (const char* file : files) {
    const std::string path = (rooms / file).string();
    const int channels = static_cast<int>(ReadAudioChannels(path).channels.size());
    for (int c = 0; c < channels; ++c) {
      const ResponseFeatures f = MeasureFeatures(LoadImpulseResponse(path, c, kRate), kRate, 2300.0, 3700.0);
      colour.Add(f.colour_db);
      direct_colour.Add(f.direct_colour_db);
      tone.Add(std::fabs(f.tone_ratio_db));
      decay.Add(f.decay_ratio);
      spread.Add(f.direct_spread_ms);
    }
  }
  std::vector<double> like[5], statistical[2];
  for (std::uint32_t seed = 1; seed <= 12; ++seed) {
    const ResponseFeatures f = MeasureFeatures(MeasuredLikeResponse(0.6, -3.0, kRate, seed), kRate, 2300.0, 3700.0);
    like[0].push_back(f.colour_db);
    like[1].push_back(f.direct_colour_db);
    like[2].push_back(std::fabs(f.tone_ratio_db));
    like[3].push_back(f.decay_ratio);
    like[4].push_back(f.direct_spread_ms);
    const ResponseFeatures s = MeasureFeatures(RoomImpulseResponse(0.6, -3.0, kRate, seed), kRate, 2300.0, 3700.0);
    statistical[0].push_back(s.colour_db);
    statistical[1].push_back(s.direct_colour_db);
  }
  const Range* measured[5] = {&colour, &direct_colour, &tone, &decay, &spread};
  const char* names[5] = {"colour_db", "direct_colour_db", "|tone_ratio_db|", "decay_ratio", "direct_spread_ms"};
  for (int k = 0; k < 5; ++k) {
    const double median = Median(like[k]);
    EXPECT_GE(median, measured[k]->low) << names[k];
    EXPECT_LE(median, measured[k]->high) << names[k];
  }
  EXPECT_LT(Median(statistical[0]), colour.low) << "the statistical response is as coloured as a measured one";
  EXPECT_LT(Median(statistical[1]), direct_colour.low) << "the statistical direct sound is as coloured as a measured one";
}

}  // namespace
}  // namespace nava_modem
