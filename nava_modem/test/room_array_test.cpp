// The room heard by a microphone array: the direct sound's per-microphone delays (measured by
// cross-correlation, to a tenth of a sample, fractional delays included) and 1/r levels, diffuse
// tails uncorrelated between microphones while the direct sound is coherent, each channel's DRR,
// per-channel noise levels, the interferer's plane wave, one output gain, determinism,
// validation, and the multi-channel WAV writer.
#include <algorithm>
#include <unistd.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "nava_modem/noise_sources.h"
#include "nava_modem/real_fft.h"
#include "nava_modem/room_array.h"
#include "nava_modem/wav_file.h"

namespace nava_modem {
namespace {

// An asymmetric array (no two pairs with the same spacing), so the delays are fractional.
std::vector<Microphone2D> TestArray() { return {{0.05, 0.0}, {0.0, 0.047}, {-0.05, 0.0}, {0.013, -0.031}}; }

// Broadband: its cross-correlation has one sharp peak.
std::vector<float> NoiseBurst(double seconds, double rate, std::uint32_t seed) {
  const std::vector<double> w = WhiteNoise(static_cast<std::size_t>(seconds * rate), seed);
  std::vector<float> x(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) x[i] = static_cast<float>(0.2 * w[i]);
  return x;
}

struct Peak {
  double lag = 0.0;          // samples, of b after a
  double correlation = 0.0;  // normalised: 1 = b is a delayed copy of a
};

// The peak of a and b's cross-correlation interpolated (spectrum zero-padded 32 times,
// band-limited like the signals) and then refined by a parabola.
Peak CrossCorrelationPeak(const std::vector<float>& a, const std::vector<float>& b) {
  const std::size_t n = FftSize(a.size() + b.size());
  const auto fa = ForwardFft(std::vector<double>(a.begin(), a.end()), n);
  const auto fb = ForwardFft(std::vector<double>(b.begin(), b.end()), n);
  constexpr std::size_t kUp = 32;
  std::vector<std::complex<double>> cross(n * kUp / 2 + 1);
  for (std::size_t k = 0; k < fa.size(); ++k) cross[k] = std::conj(fa[k]) * fb[k];
  const std::vector<double> r = InverseFft(cross, n * kUp);
  const std::size_t best = static_cast<std::size_t>(std::max_element(r.begin(), r.end()) - r.begin());
  const double left = r[(best + r.size() - 1) % r.size()], right = r[(best + 1) % r.size()];
  const double fine = static_cast<double>(best) + 0.5 * (left - right) / (left - 2.0 * r[best] + right);
  const double lag = fine > r.size() / 2.0 ? fine - static_cast<double>(r.size()) : fine;
  double ea = 0.0, eb = 0.0;
  for (float v : a) ea += static_cast<double>(v) * v;
  for (float v : b) eb += static_cast<double>(v) * v;
  // (InverseFft divides by the padded size, kUp times the correlation's own.)
  return {lag / kUp, r[best] * kUp / std::sqrt(ea * eb)};
}

double Lag(const std::vector<float>& a, const std::vector<float>& b) { return CrossCorrelationPeak(a, b).lag; }

double Energy(const std::vector<float>& x, std::size_t from = 0, std::size_t to = SIZE_MAX) {
  const std::size_t end = std::min(to, x.size());
  double e = 0.0;
  for (std::size_t i = from; i < end; ++i) e += static_cast<double>(x[i]) * x[i];
  return e;
}

// Normalised correlation of a and b over [from, to) at lag 0.
double Correlation(const std::vector<float>& a, const std::vector<float>& b, std::size_t from, std::size_t to) {
  double ab = 0.0;
  for (std::size_t i = from; i < to; ++i) ab += static_cast<double>(a[i]) * b[i];
  return ab / std::sqrt(Energy(a, from, to) * Energy(b, from, to));
}

std::vector<float> Scaled(const std::vector<float>& x, double gain) {
  std::vector<float> y(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = static_cast<float>(x[i] * gain);
  return y;
}

double GeometryDelay(const ArraySource& s, std::size_t m) {
  return std::hypot(s.distance * std::cos(s.bearing) - s.mics[m].x, s.distance * std::sin(s.bearing) - s.mics[m].y) /
         s.speed_of_sound;
}

TEST(RoomArrayTest, DirectDelaysAndLevelsFollowTheGeometry) {
  for (double rate : {16000.0, 48000.0}) {
    const std::vector<float> clean = NoiseBurst(0.2, rate, 5);
    for (double bearing : {0.3, 2.0, -2.7}) {
      for (double distance : {2.0, 0.4}) {
        SCOPED_TRACE("rate " + std::to_string(rate) + " bearing " + std::to_string(bearing) + " distance " +
                     std::to_string(distance));
        ArraySource source;
        source.mics = TestArray();
        source.bearing = bearing;
        source.distance = distance;
        ArrayRenderInfo info;
        const auto channels = RenderRoomArray(clean, rate, RoomOptions{}, source, {}, &info);
        ASSERT_EQ(channels.size(), source.mics.size());
        bool fractional = false;
        for (std::size_t m = 0; m < channels.size(); ++m) {
          ASSERT_EQ(channels[m].size(), channels[0].size());
          const double expected = GeometryDelay(source, m) * rate;
          EXPECT_NEAR(info.channels[m].direct_delay_s * rate, expected, 1e-9);
          EXPECT_NEAR(Lag(clean, channels[m]), expected, 0.1) << "mic " << m;
          // Between microphones, as a direction estimator sees them.
          EXPECT_NEAR(Lag(channels[0], channels[m]), expected - GeometryDelay(source, 0) * rate, 0.1) << "mic " << m;
          const double fraction = expected - std::floor(expected);
          fractional = fractional || (fraction > 0.2 && fraction < 0.8);
          // 1/r: the level differences are small but there.
          const double gain = distance / (GeometryDelay(source, m) * source.speed_of_sound);
          EXPECT_NEAR(info.channels[m].direct_gain, gain, 1e-12);
          EXPECT_NEAR(10.0 * std::log10(Energy(channels[m]) / Energy(channels[0])),
                      20.0 * std::log10(gain / info.channels[0].direct_gain), 0.01)
              << "mic " << m;
        }
        EXPECT_TRUE(fractional) << "no delay far from a whole sample: the case is not tested";
        EXPECT_DOUBLE_EQ(info.lead_s, 0.0);
      }
    }
  }
}

TEST(RoomArrayTest, DirectSoundCoherentDiffuseTailsNot) {
  const double rate = 16000.0;
  ArraySource source;
  source.mics = TestArray();
  source.bearing = 1.0;
  RoomOptions room;
  room.rt60 = 0.8;
  room.drr_db = -6.0;
  std::vector<float> click(1, 1.0f);
  ArrayRenderInfo info;
  const auto h = RenderRoomArray(click, rate, room, source, {}, &info);
  // After the early reflections (which end by 40 ms) to the end: the tail alone.
  const std::size_t from = static_cast<std::size_t>((info.channels[0].direct_delay_s + 0.05) * rate);
  const std::size_t to = h[0].size() - 1;
  for (std::size_t a = 0; a < h.size(); ++a) {
    for (std::size_t b = a + 1; b < h.size(); ++b) {
      EXPECT_LT(std::fabs(Correlation(h[a], h[b], from, to)), 0.2) << "mics " << a << ", " << b;
    }
  }
  // The same pairs without the room, at the (fractional) lag between them: one sound, delayed.
  const std::vector<float> clean = NoiseBurst(0.2, rate, 6);
  const auto direct = RenderRoomArray(clean, rate, RoomOptions{}, source);
  for (std::size_t b = 1; b < direct.size(); ++b) {
    EXPECT_GT(CrossCorrelationPeak(direct[0], direct[b]).correlation, 0.99) << "mic " << b;
  }
}

TEST(RoomArrayTest, EachChannelHearsTheRoomsDrr) {
  const double rate = 48000.0;
  const std::vector<float> click(1, 1.0f);
  ArraySource source;
  // Spread wide and near, so 1/r moves the channels' DRR by several dB.
  source.mics = {{0.0, 0.0}, {0.5, 0.0}, {-0.5, 0.0}, {0.0, 0.3}};
  source.distance = 1.0;
  for (double drr : {-6.0, 0.0, 6.0}) {
    for (std::uint32_t seed : {1u, 2u}) {
      SCOPED_TRACE("drr " + std::to_string(drr) + " seed " + std::to_string(seed));
      RoomOptions room;
      room.rt60 = 0.6;
      room.drr_db = drr;
      room.seed = seed;
      ArrayRenderInfo dry_info, wet_info;
      const auto dry = RenderRoomArray(click, rate, RoomOptions{}, source, {}, &dry_info);
      const auto wet = RenderRoomArray(click, rate, room, source, {}, &wet_info);
      for (std::size_t m = 0; m < wet.size(); ++m) {
        // The direct sound is the anechoic render; the rest of the reverberant one is the room.
        const std::vector<float> direct = Scaled(dry[m], 1.0 / dry_info.output_gain);
        std::vector<float> reverberant = Scaled(wet[m], 1.0 / wet_info.output_gain);
        for (std::size_t i = 0; i < direct.size(); ++i) reverberant[i] -= direct[i];
        const double measured = 10.0 * std::log10(Energy(direct) / Energy(reverberant));
        const double expected = drr + 20.0 * std::log10(wet_info.channels[m].direct_gain);
        EXPECT_NEAR(measured, expected, 0.5) << "mic " << m;
        EXPECT_NEAR(wet_info.channels[m].drr_db, expected, 1e-9) << "mic " << m;
      }
      EXPECT_NEAR(wet_info.channels[1].drr_db - drr, 20.0 * std::log10(2.0), 1e-9);  // half as far
    }
  }
}

TEST(RoomArrayTest, NoiseIndependentPerChannelAtEachChannelsSnr) {
  const double rate = 16000.0;
  std::vector<float> clean(static_cast<std::size_t>(0.3 * rate), 0.0f);
  const std::vector<float> burst = NoiseBurst(0.6, rate, 7);
  clean.insert(clean.end(), burst.begin(), burst.end());
  clean.resize(clean.size() + static_cast<std::size_t>(0.3 * rate), 0.0f);
  ArraySource source;
  source.mics = {{0.0, 0.0}, {0.4, 0.0}, {0.0, -0.4}};
  source.distance = 0.8;
  RoomOptions room;
  room.rt60 = 0.3;
  ArrayRenderInfo quiet_info, loud_info;
  const auto quiet = RenderRoomArray(clean, rate, room, source, {}, &quiet_info);
  room.noise = RoomOptions::Noise::kPink;
  room.snr_db = 10.0;
  const auto loud = RenderRoomArray(clean, rate, room, source, {}, &loud_info);
  std::vector<std::vector<float>> noise(loud.size());
  float peak = 0.0f;
  for (std::size_t m = 0; m < loud.size(); ++m) {
    const std::vector<float> signal = Scaled(quiet[m], 1.0 / quiet_info.output_gain);
    noise[m] = Scaled(loud[m], 1.0 / loud_info.output_gain);
    for (std::size_t i = 0; i < signal.size(); ++i) noise[m][i] -= signal[i];
    // The burst as this microphone hears it (the level definition's sounding samples, shifted).
    const std::size_t from = static_cast<std::size_t>(std::lround((0.3 + loud_info.channels[m].direct_delay_s) * rate));
    const std::size_t to = from + burst.size();
    const double snr = 10.0 * std::log10((Energy(signal, from, to) / burst.size()) / (Energy(noise[m]) / noise[m].size()));
    EXPECT_NEAR(snr, 10.0, 0.2) << "mic " << m;
    for (float v : loud[m]) peak = std::max(peak, std::fabs(v));
  }
  EXPECT_NEAR(peak, kRoomPeak, 1e-6);  // the loudest channel, one gain for all
  // The near microphone (1) hears the modem louder, and so gets louder noise for the same SNR.
  EXPECT_GT(loud_info.channels[1].noise_rms, loud_info.channels[0].noise_rms);
  for (std::size_t a = 0; a < noise.size(); ++a) {
    for (std::size_t b = a + 1; b < noise.size(); ++b) {
      EXPECT_LT(std::fabs(Correlation(noise[a], noise[b], 0, noise[a].size())), 0.05) << "mics " << a << ", " << b;
    }
  }
}

TEST(RoomArrayTest, InterfererIsAPlaneWaveFromItsBearing) {
  const double rate = 16000.0;
  const std::vector<float> clean = NoiseBurst(0.3, rate, 8);
  const std::vector<float> interferer = NoiseBurst(0.45, rate, 9);
  ArraySource source;
  source.mics = {{0.2, 0.0}, {-0.2, 0.0}, {0.0, 0.2}};
  RoomOptions o;
  o.seed = 3;
  ArrayRenderInfo quiet_info, loud_info;
  const auto quiet = RenderRoomArray(clean, rate, o, source, {}, &quiet_info);
  o.sir_db = -3.0;
  const auto loud = RenderRoomArray(clean, rate, o, source, interferer, &loud_info);
  EXPECT_EQ(loud_info.interferer_bearing, quiet_info.interferer_bearing);  // drawn whether used or not
  std::vector<std::vector<float>> heard(loud.size());
  for (std::size_t m = 0; m < loud.size(); ++m) {
    const std::vector<float> signal = Scaled(quiet[m], 1.0 / quiet_info.output_gain);
    heard[m] = Scaled(loud[m], 1.0 / loud_info.output_gain);
    for (std::size_t i = 0; i < signal.size(); ++i) heard[m][i] -= signal[i];
  }
  const double u[2] = {std::cos(loud_info.interferer_bearing), std::sin(loud_info.interferer_bearing)};
  for (std::size_t m = 1; m < heard.size(); ++m) {
    // A plane wave from u reaches p earlier by p.u / c.
    const double expected = ((source.mics[0].x - source.mics[m].x) * u[0] + (source.mics[0].y - source.mics[m].y) * u[1]) /
                            source.speed_of_sound * rate;
    // The middle of the channels: the loop's ends are not a clean delay of each other.
    const std::size_t cut = heard[0].size() / 4;
    const std::vector<float> a(heard[0].begin() + cut, heard[0].end() - cut), b(heard[m].begin() + cut, heard[m].end() - cut);
    EXPECT_NEAR(Lag(a, b), expected, 0.1) << "mic " << m;
    // The same wave in every channel, scaled to each channel's own SIR.
    EXPECT_NEAR(Energy(heard[m]) / Energy(heard[0]),
                loud_info.channels[m].signal_power / loud_info.channels[0].signal_power, 0.02)
        << "mic " << m;
  }
}

TEST(RoomArrayTest, SameSeedSameRenderOtherSeedOtherRoom) {
  const double rate = 16000.0;
  const std::vector<float> clean = NoiseBurst(0.2, rate, 10);
  ArraySource source;
  source.mics = TestArray();
  RoomOptions o;
  o.rt60 = 0.4;
  o.noise = RoomOptions::Noise::kWhite;
  o.whine_hz = 500.0;
  o.seed = 11;
  const auto a = RenderRoomArray(clean, rate, o, source, NoiseBurst(0.1, rate, 12));
  EXPECT_EQ(a, RenderRoomArray(clean, rate, o, source, NoiseBurst(0.1, rate, 12)));
  o.seed = 12;
  const auto b = RenderRoomArray(clean, rate, o, source, NoiseBurst(0.1, rate, 12));
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NE(a[0], b[0]);
  EXPECT_NE(a[0], a[1]);
  // Empty in, empty channels out.
  const auto empty = RenderRoomArray({}, rate, o, source);
  ASSERT_EQ(empty.size(), source.mics.size());
  EXPECT_TRUE(empty[0].empty());
}

TEST(RoomArrayTest, FarMicrophonesHearNothingBeforeTimeZero) {
  // A microphone 5 m out would hear a plane-wave reflection from its side before the source
  // plays; everything moves later by the lead instead, and the delays between channels stay.
  ArraySource source;
  source.mics = {{0.0, 0.0}, {5.0, 0.0}, {-5.0, 0.0}, {0.0, 5.0}, {0.0, -5.0}};
  source.distance = 0.5;
  RoomOptions o;
  o.rt60 = 0.3;
  ArrayRenderInfo info;
  RenderRoomArray(std::vector<float>(1, 1.0f), 16000.0, o, source, {}, &info);
  EXPECT_GT(info.lead_s, 0.0);
  EXPECT_NEAR(info.channels[1].direct_delay_s - info.channels[0].direct_delay_s,
              (GeometryDelay(source, 1) - GeometryDelay(source, 0)), 1e-12);
}

TEST(RoomArrayTest, ValidationNamesTheField) {
  auto field_of = [](const ArraySource& s) -> std::string {
    try {
      ValidateArraySource(s);
    } catch (const RoomOptionError& e) {
      return e.field() + ": " + e.what();
    }
    return "";
  };
  ArraySource s;
  EXPECT_EQ(field_of(s), "mics: no microphones: expected at least one");
  s.mics = {{0.1, 0.0}, {0.0, 0.1}, {0.1, 0.0}};
  EXPECT_EQ(field_of(s), "mics: microphones 1 and 3 both at (0.1, 0) m: expected distinct positions");
  s.mics = {{0.1, NAN}};
  EXPECT_EQ(field_of(s), "mics: microphone 1 at (0.1, nan) m: expected finite coordinates");
  s.mics = TestArray();
  EXPECT_EQ(field_of(s), "");
  s.distance = 0.0;
  EXPECT_EQ(field_of(s), "distance: distance 0 m: expected above 0 and at most 100 m");
  s.distance = 101.0;
  EXPECT_NE(field_of(s).find("at most 100 m"), std::string::npos);
  s.distance = 0.05;  // on microphone 1, at (0.05, 0)
  EXPECT_NE(field_of(s).find("0 m from microphone 1, expected at least 0.01 m"), std::string::npos);
  s.distance = 2.0;
  s.bearing = INFINITY;
  EXPECT_EQ(field_of(s), "bearing: bearing inf rad: expected a finite angle");
  s.bearing = 0.0;
  s.speed_of_sound = 0.0;
  EXPECT_EQ(field_of(s), "speed_of_sound: speed_of_sound 0 m/s: expected above 0");
  s.speed_of_sound = 343.0;
  RoomOptions bad;
  bad.rt60 = -1.0;
  EXPECT_THROW(RenderRoomArray({0.5f}, 16000.0, bad, s), RoomOptionError);
  RoomOptions noisy;
  noisy.noise = RoomOptions::Noise::kWhite;
  EXPECT_THROW(RenderRoomArray({0.0f, 0.0f}, 16000.0, noisy, s), std::invalid_argument);  // silence: no level for the noise
}

TEST(WavChannelsTest, WritesInterleavedChannelsAndRefusesRaggedOnes) {
  const std::string path = ::testing::TempDir() + "/room_array_test_channels_" + std::to_string(getpid()) + ".wav";
  const std::vector<std::vector<float>> channels = {{0.5f, -0.25f, 0.0f}, {0.25f, 0.25f, -0.5f}, {0.0f, 0.5f, 0.5f}};
  WriteWavChannels(path, channels, 16000.0);
  const Audio mixed = ReadAudioFile(path);  // mixes the channels to one: their mean
  ASSERT_EQ(mixed.samples.size(), 3u);
  EXPECT_EQ(mixed.sample_rate, 16000.0);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(mixed.samples[i], (channels[0][i] + channels[1][i] + channels[2][i]) / 3.0, 1.0 / 32768);
  }
  std::remove(path.c_str());
  try {
    WriteWavChannels(path, {{0.1f, 0.2f}, {0.1f}}, 16000.0);
    FAIL() << "ragged channels written";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": channel 2 has 1 samples"), std::string::npos) << e.what();
  }
  EXPECT_THROW(WriteWavChannels(path, {}, 16000.0), std::runtime_error);
  EXPECT_THROW(WriteWavChannels("/nonexistent/dir/x.wav", channels, 16000.0), std::runtime_error);
}

}  // namespace
}  // namespace nava_modem
