// The room channel: its impulse response (RT60 by Schroeder integration, DRR), the tilt, the
// clock offset, the levels of noise, interferer and whine measured on the output, validation,
// determinism, at 16, 44.1 and 48 kHz.
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "nava_modem/noise_sources.h"
#include "nava_modem/real_fft.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/room_impulse_response.h"

namespace nava_modem {
namespace {

constexpr double kTwoPi = 6.283185307179586;
const double kRates[] = {16000.0, 44100.0, 48000.0};

std::vector<float> Tone(double hz, double seconds, double sample_rate, double amplitude = 0.5) {
  std::vector<float> x(static_cast<std::size_t>(seconds * sample_rate));
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = static_cast<float>(amplitude * std::sin(kTwoPi * hz * i / sample_rate));
  return x;
}

void Append(std::vector<float>& to, const std::vector<float>& what) { to.insert(to.end(), what.begin(), what.end()); }

double MeanSquare(const std::vector<float>& x, std::size_t from, std::size_t to) {
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) sum += static_cast<double>(x[i]) * x[i];
  return sum / static_cast<double>(to - from);
}

// Only the spectrum's bins in [lo_hz, hi_hz), zero-padded so that the brick wall's ringing
// does not wrap onto the decay.
std::vector<float> BandPass(const std::vector<float>& x, double sample_rate, double lo_hz, double hi_hz) {
  const std::size_t size = FftSize(2 * x.size());
  std::vector<std::complex<double>> spectrum = ForwardFft(std::vector<double>(x.begin(), x.end()), size);
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    const double f = BinHz(k, size, sample_rate);
    if (f < lo_hz || f >= hi_hz) spectrum[k] = 0.0;
  }
  const std::vector<double> y = InverseFft(spectrum, size);
  return std::vector<float>(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(x.size()));
}

// Reverberation time by Schroeder backward integration: the energy decay curve in dB, a least
// squares line through its -5 to -25 dB stretch (T20), extrapolated to 60 dB.
double SchroederRt60(const std::vector<float>& h, double sample_rate) {
  std::vector<double> edc(h.size());
  double sum = 0.0;
  for (std::size_t i = h.size(); i-- > 0;) edc[i] = (sum += static_cast<double>(h[i]) * h[i]);
  double st = 0, sd = 0, stt = 0, std_ = 0;
  int n = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double db = 10.0 * std::log10(edc[i] / edc[0]);
    if (db > -5.0) continue;
    if (db < -25.0) break;
    const double t = i / sample_rate;
    st += t, sd += db, stt += t * t, std_ += t * db, ++n;
  }
  const double slope = (n * std_ - st * sd) / (n * stt - st * st);  // dB per second
  return -60.0 / slope;
}

// Frequency of a steady tone from its zero crossings (interpolated) between `from` and `to`.
double ToneFrequency(const std::vector<float>& x, double sample_rate, std::size_t from, std::size_t to) {
  double first = -1.0, last = -1.0;
  int crossings = 0;
  for (std::size_t i = from; i + 1 < to; ++i) {
    if (x[i] <= 0.0f && x[i + 1] > 0.0f) {
      const double t = i + x[i] / static_cast<double>(x[i] - x[i + 1]);
      if (first < 0.0) first = t;
      last = t;
      ++crossings;
    }
  }
  return (crossings - 1) * sample_rate / (last - first);
}

// ---- The impulse response ----

TEST(RoomImpulseResponseTest, NoRoomIsTheDirectSoundAlone) {
  EXPECT_EQ(RoomImpulseResponse(0.0, 5.0, 48000.0, 1), std::vector<float>{1.0f});
}

struct Rt60Case {
  double rt60, sample_rate;
};

class Rt60Test : public ::testing::TestWithParam<Rt60Case> {};

// rt60 is the decay below kRoomCrossoverHz (room_impulse_response.h), measured there; above it
// the tail decays in kHighBandDecayRatio x rt60.
TEST_P(Rt60Test, SchroederDecayAndDrrAreAsAsked) {
  const auto [rt60, rate] = GetParam();
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    for (double drr : {-6.0, 0.0, 6.0}) {
      const std::vector<float> h = RoomImpulseResponse(rt60, drr, rate, seed);
      SCOPED_TRACE("seed " + std::to_string(seed) + " drr " + std::to_string(drr));
      EXPECT_EQ(h[0], 1.0f);
      EXPECT_NEAR(h.size() / rate, 1.2 * rt60, 1.0 / rate + 1e-9);
      EXPECT_NEAR(MeasureDrrDb(h), drr, 0.5);
      EXPECT_NEAR(MeasureDrrDb(h), drr, 0.01);  // by construction, not just within the tolerance
      std::vector<float> reverberant = h;
      reverberant[0] = 0.0f;  // T20 from -5 dB would start on a strong direct sound otherwise
      const double low = SchroederRt60(BandPass(reverberant, rate, 0.0, kRoomCrossoverHz), rate);
      EXPECT_NEAR(low, rt60, 0.15 * rt60);
      const double high = SchroederRt60(BandPass(reverberant, rate, kRoomCrossoverHz, rate / 2.0), rate);
      EXPECT_NEAR(high, kHighBandDecayRatio * rt60, 0.15 * kHighBandDecayRatio * rt60);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(RoomImpulseResponseTest, Rt60Test,
                         ::testing::Values(Rt60Case{0.3, 16000}, Rt60Case{0.6, 16000}, Rt60Case{1.0, 16000},
                                           Rt60Case{0.3, 44100}, Rt60Case{0.6, 44100}, Rt60Case{1.0, 44100},
                                           Rt60Case{0.3, 48000}, Rt60Case{0.6, 48000}, Rt60Case{1.0, 48000}));

TEST(RoomImpulseResponseTest, SameSeedSameRoomOtherSeedOtherRoom) {
  EXPECT_EQ(RoomImpulseResponse(0.5, 0.0, 48000, 7), RoomImpulseResponse(0.5, 0.0, 48000, 7));
  EXPECT_NE(RoomImpulseResponse(0.5, 0.0, 48000, 7), RoomImpulseResponse(0.5, 0.0, 48000, 8));
}

TEST(RoomImpulseResponseTest, RejectsOutOfRangeArguments) {
  EXPECT_THROW(RoomImpulseResponse(-0.1, 0.0, 48000, 1), std::invalid_argument);
  EXPECT_THROW(RoomImpulseResponse(11.0, 0.0, 48000, 1), std::invalid_argument);
  EXPECT_THROW(RoomImpulseResponse(0.5, 41.0, 48000, 1), std::invalid_argument);
  EXPECT_THROW(RoomImpulseResponse(0.5, 0.0, 0.0, 1), std::invalid_argument);
}

// ---- Tilt and clock ----

TEST(RoomChannelTest, TiltGainsAtTheCornersAndBetween) {
  for (double rate : kRates) {
    SCOPED_TRACE(rate);
    RoomOptions o;
    o.tilt_db = -12.0;
    // Bursts 0.3 s long, 0.1 s apart; each burst's level relative to the 1000 Hz one (in the flat
    // part below the band).
    const double hz[] = {1000.0, o.tilt_low_hz, std::sqrt(o.tilt_low_hz * o.tilt_high_hz), o.tilt_high_hz, 6000.0};
    const double expected_db[] = {0.0, 0.0, -6.0, -12.0, -12.0};
    std::vector<float> clean(static_cast<std::size_t>(0.1 * rate), 0.0f);
    std::vector<std::size_t> starts;
    for (double f : hz) {
      starts.push_back(clean.size());
      Append(clean, Tone(std::min(f, 0.45 * rate), 0.3, rate));
      Append(clean, std::vector<float>(static_cast<std::size_t>(0.1 * rate), 0.0f));
    }
    const std::vector<float> out = RenderRoom(clean, rate, o, {});
    ASSERT_EQ(out.size(), clean.size());
    const std::size_t skip = static_cast<std::size_t>(0.05 * rate), len = static_cast<std::size_t>(0.2 * rate);
    const double reference = MeanSquare(out, starts[0] + skip, starts[0] + skip + len);
    for (std::size_t k = 0; k < starts.size(); ++k) {
      const double db = 10.0 * std::log10(MeanSquare(out, starts[k] + skip, starts[k] + skip + len) / reference);
      EXPECT_NEAR(db, expected_db[k], 0.5) << hz[k] << " Hz";
      EXPECT_NEAR(TiltGainDb(o, hz[k]), expected_db[k], 1e-9);
    }
  }
}

TEST(RoomChannelTest, ClockOffsetMovesFrequenciesAndShortensSounds) {
  for (double rate : kRates) {
    SCOPED_TRACE(rate);
    RoomOptions o;
    o.clock_offset = 0.01;
    const std::vector<float> clean = Tone(3000.0, 1.0, rate);
    const std::vector<float> out = RenderRoom(clean, rate, o, {});
    EXPECT_NEAR(static_cast<double>(out.size()), clean.size() / 1.01, 2.0);
    EXPECT_NEAR(ToneFrequency(out, rate, out.size() / 10, out.size() * 9 / 10), 3030.0, 0.5);
    o.clock_offset = -0.02;
    const std::vector<float> slow = RenderRoom(clean, rate, o, {});
    EXPECT_NEAR(ToneFrequency(slow, rate, slow.size() / 10, slow.size() * 9 / 10), 2940.0, 0.5);
  }
}

TEST(RoomChannelTest, ResampleKeepsTheToneAndScalesTheLength) {
  const std::vector<float> in = Tone(1000.0, 1.0, 22050.0);
  const std::vector<float> out = Resample(in, 48000.0 / 22050.0);
  EXPECT_NEAR(static_cast<double>(out.size()), 48000.0, 2.0);
  EXPECT_NEAR(ToneFrequency(out, 48000.0, 4800, 43200), 1000.0, 0.2);
  EXPECT_NEAR(MeanSquare(out, 4800, 43200), 0.125, 0.125 * 0.01);  // level kept
  EXPECT_THROW(Resample(in, 0.0), std::invalid_argument);
}

// ---- Levels ----

// Three 0.4 s packets-like bursts (mark/space tones alternating every 10 ms) 0.3 s apart.
struct Bursts {
  std::vector<float> clean;
  std::vector<std::pair<std::size_t, std::size_t>> spans;
};

Bursts MakeBursts(double rate) {
  Bursts b;
  const std::size_t gap = static_cast<std::size_t>(0.3 * rate), len = static_cast<std::size_t>(0.4 * rate);
  b.clean.assign(gap, 0.0f);
  for (int k = 0; k < 3; ++k) {
    const std::size_t start = b.clean.size();
    for (std::size_t i = 0; i < len; ++i) {
      const double f = (i / static_cast<std::size_t>(0.01 * rate)) % 2 ? 2300.0 : 3700.0;
      b.clean.push_back(static_cast<float>(0.5 * std::sin(kTwoPi * f * i / rate)));
    }
    b.spans.push_back({start, start + len});
    b.clean.insert(b.clean.end(), gap, 0.0f);
  }
  return b;
}

// The ratio, dB, of the modem signal's power during the bursts to the power of what was added,
// from two renders with the same options but for the disturbance: the quiet one, scaled to the
// other by least squares (the disturbance is uncorrelated with the signal), is the signal; what
// is left over is the disturbance.
double MeasuredRatioDb(const std::vector<float>& quiet, const std::vector<float>& loud, const Bursts& b) {
  double qq = 0.0, ql = 0.0;
  for (std::size_t i = 0; i < quiet.size(); ++i) qq += static_cast<double>(quiet[i]) * quiet[i], ql += static_cast<double>(quiet[i]) * loud[i];
  const double k = ql / qq;
  double signal = 0.0, rest = 0.0;
  std::size_t count = 0;
  for (const auto& [from, to] : b.spans) {
    for (std::size_t i = from; i < to; ++i) signal += k * quiet[i] * k * quiet[i], ++count;
  }
  for (std::size_t i = 0; i < quiet.size(); ++i) rest += (loud[i] - k * quiet[i]) * (loud[i] - k * quiet[i]);
  return 10.0 * std::log10((signal / count) / (rest / quiet.size()));
}

// A spoken-like interferer: 0.37 s (so that it loops) of three tones, syllable-rate modulated.
std::vector<float> Interferer(double rate) {
  std::vector<float> x(static_cast<std::size_t>(0.37 * rate));
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / rate;
    x[i] = static_cast<float>((0.3 + 0.3 * std::sin(kTwoPi * 4.0 * t)) *
                              (std::sin(kTwoPi * 440.0 * t) + 0.5 * std::sin(kTwoPi * 1320.0 * t) + 0.3 * std::sin(kTwoPi * 2900.0 * t)));
  }
  return x;
}

TEST(RoomChannelTest, NoiseInterfererAndWhineAtTheirRatios) {
  for (double rate : kRates) {
    const Bursts b = MakeBursts(rate);
    RoomOptions room;
    room.rt60 = 0.4;
    room.drr_db = 0.0;
    room.tilt_db = -3.0;
    const std::vector<float> quiet = RenderRoom(b.clean, rate, room, {});
    for (double ratio : {-6.0, 10.0, 20.0}) {
      SCOPED_TRACE("rate " + std::to_string(rate) + " ratio " + std::to_string(ratio));
      RoomOptions o = room;
      o.noise = RoomOptions::Noise::kWhite;
      o.snr_db = ratio;
      EXPECT_NEAR(MeasuredRatioDb(quiet, RenderRoom(b.clean, rate, o, {}), b), ratio, 0.5) << "white";
      o.noise = RoomOptions::Noise::kPink;
      EXPECT_NEAR(MeasuredRatioDb(quiet, RenderRoom(b.clean, rate, o, {}), b), ratio, 0.5) << "pink";
      o = room;
      o.sir_db = ratio;
      EXPECT_NEAR(MeasuredRatioDb(quiet, RenderRoom(b.clean, rate, o, Interferer(rate)), b), ratio, 0.5) << "interferer";
      o = room;
      o.whine_hz = 700.0;
      o.whine_sir_db = ratio;
      EXPECT_NEAR(MeasuredRatioDb(quiet, RenderRoom(b.clean, rate, o, {}), b), ratio, 0.5) << "whine";
    }
  }
}

TEST(RoomChannelTest, PinkNoiseFallsThreeDbPerOctave) {
  const double rate = 48000.0;
  const std::vector<double> pink = PinkNoise(1 << 18, rate, 3);
  const std::size_t size = pink.size();
  const std::vector<std::complex<double>> spectrum = ForwardFft(pink, size);
  auto band_density = [&](double lo, double hi) {
    double sum = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < spectrum.size(); ++k) {
      const double f = BinHz(k, size, rate);
      if (f >= lo && f < hi) sum += std::norm(spectrum[k]), ++n;
    }
    return sum / n;
  };
  // Octave 1-2 kHz vs 4-8 kHz: two octaves, 6 dB less density.
  EXPECT_NEAR(10.0 * std::log10(band_density(4000, 8000) / band_density(1000, 2000)), -6.0, 0.5);
}

TEST(RoomChannelTest, OutputPeakAndLength) {
  const Bursts b = MakeBursts(44100.0);
  RoomOptions o;
  o.rt60 = 0.5;
  o.noise = RoomOptions::Noise::kPink;
  RoomRenderInfo info;
  const std::vector<float> out = RenderRoom(b.clean, 44100.0, o, {}, &info);
  EXPECT_EQ(out.size(), b.clean.size() + RoomImpulseResponse(0.5, 0.0, 44100.0, 1).size() - 1);
  float peak = 0.0f;
  for (float v : out) peak = std::max(peak, std::fabs(v));
  EXPECT_NEAR(peak, kRoomPeak, 1e-6);
  EXPECT_NEAR(info.measured_drr_db, 0.0, 0.01);
  // 1.2 s of bursts, each widened by about 5 ms either side by the 10 ms envelope window.
  EXPECT_NEAR(info.sounding_fraction, (1.2 + 6 * 0.005) / (b.clean.size() / 44100.0), 0.002);
  EXPECT_TRUE(RenderRoom({}, 44100.0, o, {}).empty());
}

TEST(RoomChannelTest, SoundingSamplesFollowTheEnvelope) {
  const double rate = 16000.0;
  std::vector<float> x(1600, 0.0f);
  Append(x, Tone(1000.0, 0.2, rate));
  Append(x, std::vector<float>(1600, 0.0f));
  const std::vector<bool> s = SoundingSamples(x, rate);
  EXPECT_FALSE(s[1600 - 80]);  // more than half the 10 ms window before the tone
  EXPECT_TRUE(s[1600]);
  EXPECT_TRUE(s[1600 + 3199]);
  EXPECT_FALSE(s[1600 + 3200 + 80]);
  // Widened either side by the window's half-width (80) less the ~2 samples that reach -20 dB.
  EXPECT_NEAR(std::count(s.begin(), s.end(), true), 3200 + 2 * 78, 4);
  const std::vector<bool> silent = SoundingSamples(std::vector<float>(100, 0.0f), rate);
  EXPECT_EQ(std::count(silent.begin(), silent.end(), true), 0);
}

TEST(RoomChannelTest, SilentSignalHasNoLevelToReferTo) {
  RoomOptions o;
  o.noise = RoomOptions::Noise::kWhite;
  EXPECT_THROW(RenderRoom(std::vector<float>(1000, 0.0f), 16000.0, o, {}), std::invalid_argument);
  o.noise = RoomOptions::Noise::kNone;
  EXPECT_THROW(RenderRoom(Tone(500, 0.1, 16000.0), 16000.0, o, std::vector<float>(10, 0.0f)), std::invalid_argument);
}

// ---- Validation and determinism ----

TEST(RoomChannelTest, ValidationNamesTheField) {
  const std::vector<std::pair<std::string, std::function<void(RoomOptions&)>>> cases = {
      {"rt60", [](RoomOptions& o) { o.rt60 = -1.0; }},
      {"rt60", [](RoomOptions& o) { o.rt60 = 10.5; }},
      {"rt60", [](RoomOptions& o) { o.rt60 = std::nan(""); }},
      {"drr_db", [](RoomOptions& o) { o.drr_db = 50.0; }},
      {"drr_db", [](RoomOptions& o) { o.drr_db = -41.0; }},
      {"tilt_db", [](RoomOptions& o) { o.tilt_db = 45.0; }},
      {"tilt_low_hz", [](RoomOptions& o) { o.tilt_low_hz = 0.0; }},
      {"tilt_high_hz", [](RoomOptions& o) { o.tilt_high_hz = 2000.0; }},
      {"clock_offset", [](RoomOptions& o) { o.clock_offset = 0.06; }},
      {"snr_db", [](RoomOptions& o) { o.snr_db = -61.0; }},
      {"sir_db", [](RoomOptions& o) { o.sir_db = 101.0; }},
      {"whine_sir_db", [](RoomOptions& o) { o.whine_sir_db = 200.0; }},
      {"whine_hz", [](RoomOptions& o) { o.whine_hz = 8000.0; }},
      {"whine_hz", [](RoomOptions& o) { o.whine_hz = -5.0; }},
      {"whine_am_hz", [](RoomOptions& o) { o.whine_am_hz = -1.0; }},
      {"noise", [](RoomOptions& o) { o.noise = static_cast<RoomOptions::Noise>(7); }},
      {"model", [](RoomOptions& o) { o.model = static_cast<RoomOptions::Model>(5); }},
      {"model", [](RoomOptions& o) {
         o.model = RoomOptions::Model::kMeasuredLike;
         o.response = {1.0f, 0.5f};
       }},
      {"geometry", [](RoomOptions& o) {
         o.rt60 = 0.5;
         o.geometry.distance_m = 3.0;  // the statistical room has no geometry to put it in
       }},
  };
  for (const auto& [field, spoil] : cases) {
    RoomOptions o;
    spoil(o);
    try {
      ValidateRoomOptions(o, 16000.0);
      ADD_FAILURE() << field << " accepted";
    } catch (const RoomOptionError& e) {
      EXPECT_EQ(e.field(), field);
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(field + " ", 0), 0u) << what;
      EXPECT_NE(what.find("expected"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    EXPECT_THROW(RenderRoom(Tone(500, 0.1, 16000.0), 16000.0, o, {}), std::invalid_argument) << field;
  }
  try {
    RoomOptions o;
    o.rt60 = -1.0;
    ValidateRoomOptions(o, 48000.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "rt60 -1 s: expected 0 (no reverberation) or above 0 and at most 10");
  }
  EXPECT_NO_THROW(ValidateRoomOptions(RoomOptions{}, 16000.0));
  EXPECT_THROW(ValidateRoomOptions(RoomOptions{}, 0.0), RoomOptionError);
}

TEST(RoomChannelTest, NamesItsModelsAndGivesAMeasuredLikeRoomItsGeometry) {
  for (const auto model : {RoomOptions::Model::kStatistical, RoomOptions::Model::kMeasuredLike,
                           RoomOptions::Model::kMeasured}) {
    EXPECT_EQ(ParseRoomModel(RoomModelName(model)), model);
  }
  EXPECT_FALSE(ParseRoomModel("measured_like"));
  const double rate = 48000.0;
  const std::vector<float> clean = Tone(2300, 0.05, rate);
  RoomOptions o;
  o.rt60 = 0.5;
  o.model = RoomOptions::Model::kMeasuredLike;
  const std::vector<float> drawn = RenderRoom(clean, rate, o, {});
  o.geometry.distance_m = 7.5;
  const std::vector<float> placed = RenderRoom(clean, rate, o, {});
  EXPECT_NE(drawn, placed);  // the reflections' delays follow the given distance
  EXPECT_EQ(placed, RenderRoom(clean, rate, o, {}));
}

TEST(RoomChannelTest, SameSeedSameOutput) {
  const Bursts b = MakeBursts(16000.0);
  RoomOptions o;
  o.rt60 = 0.3;
  o.clock_offset = 0.005;
  o.tilt_db = -6.0;
  o.noise = RoomOptions::Noise::kPink;
  o.whine_hz = 900.0;
  o.seed = 11;
  const std::vector<float> a = RenderRoom(b.clean, 16000.0, o, Interferer(16000.0));
  EXPECT_EQ(a, RenderRoom(b.clean, 16000.0, o, Interferer(16000.0)));
  o.seed = 12;
  EXPECT_NE(a, RenderRoom(b.clean, 16000.0, o, Interferer(16000.0)));
}

}  // namespace
}  // namespace nava_modem
