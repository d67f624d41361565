#pragma once

// Test-only impairments for the FSK receiver's tests, beside nava_room's renderer (rooms):
// packets of random data, a spectral tilt between the two tones as a shelf or a peaking cut
// (biquads, as sox's equalizer), white noise at an in-band SNR. Seeded, so
// that a test sees the same audio every run.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <random>
#include <vector>

#include "nava_modem/frame.h"
#include "nava_modem/fsk_modulator.h"

namespace nava_modem::test_signals {

// A biquad (direct form I).
struct Biquad {
  double b0, b1, b2, a1, a2;
  std::complex<double> Response(double hz, double sample_rate) const {
    const std::complex<double> z1 = std::polar(1.0, -2.0 * M_PI * hz / sample_rate), z2 = z1 * z1;
    return (b0 + b1 * z1 + b2 * z2) / (1.0 + a1 * z1 + a2 * z2);
  }
  void Run(std::vector<float>& x) const {
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    for (float& v : x) {
      const double y = b0 * v + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
      x2 = x1;
      x1 = v;
      y2 = y1;
      y1 = y;
      v = static_cast<float>(y);
    }
  }
};

// RBJ's high shelf at `hz`, gain_db above it, slope 1.
inline Biquad HighShelf(double hz, double gain_db, double sample_rate) {
  const double a = std::pow(10.0, gain_db / 40.0), w = 2.0 * M_PI * hz / sample_rate;
  const double cw = std::cos(w), alpha = std::sin(w) / 2.0 * std::sqrt(2.0);
  const double sa = 2.0 * std::sqrt(a) * alpha;
  const double a0 = (a + 1) - (a - 1) * cw + sa;
  return {a * ((a + 1) + (a - 1) * cw + sa) / a0, -2 * a * ((a - 1) + (a + 1) * cw) / a0,
          a * ((a + 1) + (a - 1) * cw - sa) / a0, 2 * ((a - 1) - (a + 1) * cw) / a0, ((a + 1) - (a - 1) * cw - sa) / a0};
}

// RBJ's peaking equaliser at `hz`, gain_db at its centre, `bandwidth_hz` wide (as sox's
// `equalizer HZ BANDWIDTHh GAIN`).
inline Biquad PeakingEq(double hz, double bandwidth_hz, double gain_db, double sample_rate) {
  const double a = std::pow(10.0, gain_db / 40.0), w = 2.0 * M_PI * hz / sample_rate;
  const double alpha = std::sin(w) / (2.0 * hz / bandwidth_hz), cw = std::cos(w);
  const double a0 = 1.0 + alpha / a;
  return {(1.0 + alpha * a) / a0, -2.0 * cw / a0, (1.0 - alpha * a) / a0, -2.0 * cw / a0, (1.0 - alpha / a) / a0};
}

// Tilts the spectrum with a shelf between the tones so that `high_hz` ends up tilt_db above
// `low_hz` (negative: below), then scales so that the louder of the two keeps its level.
inline void Tilt(std::vector<float>& x, double low_hz, double high_hz, double tilt_db, double sample_rate) {
  if (tilt_db == 0.0) return;
  // The shelf's gain that gives the wanted difference between the two tones (monotonic).
  double lo = -80.0, hi = 80.0;
  Biquad f{};
  for (int it = 0; it < 60; ++it) {
    const double g = (lo + hi) / 2.0;
    f = HighShelf(std::sqrt(low_hz * high_hz), g, sample_rate);
    const double diff = 20.0 * std::log10(std::abs(f.Response(high_hz, sample_rate)) / std::abs(f.Response(low_hz, sample_rate)));
    (diff < tilt_db ? lo : hi) = g;
  }
  const double louder = std::max(std::abs(f.Response(high_hz, sample_rate)), std::abs(f.Response(low_hz, sample_rate)));
  f.b0 /= louder;
  f.b1 /= louder;
  f.b2 /= louder;
  f.Run(x);
}

// White Gaussian noise whose power in the band [lo_hz, hi_hz] is snr_db below reference_power.
inline void AddNoise(std::vector<float>& x, double reference_power, double snr_db, double sample_rate, unsigned seed,
                     double lo_hz = 2000.0, double hi_hz = 4000.0) {
  const double in_band = reference_power / std::pow(10.0, snr_db / 10.0);
  const double sigma = std::sqrt(in_band * (sample_rate / 2.0) / (hi_hz - lo_hz));
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, sigma);
  for (float& v : x) v += static_cast<float>(g(rng));
}

inline std::vector<std::vector<std::uint8_t>> RandomPayloads(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::vector<std::uint8_t>> out(count, std::vector<std::uint8_t>(kDataBytes));
  for (auto& p : out)
    for (auto& b : p) b = static_cast<std::uint8_t>(byte(rng));
  return out;
}

// `payloads` as `modulate` sounds each, with `gap` samples of silence before each and after the
// last.
template <typename Modulate>
std::vector<float> Train(const std::vector<std::vector<std::uint8_t>>& payloads, std::size_t gap, Modulate modulate) {
  std::vector<float> audio(gap, 0.0f);
  for (const auto& p : payloads) {
    const std::vector<float> burst = modulate(p);
    audio.insert(audio.end(), burst.begin(), burst.end());
    audio.insert(audio.end(), gap, 0.0f);
  }
  return audio;
}

// The packets with gap_s of silence before each and after the last, sent by a sound card
// whose clock runs (1 + clock_error) fast: tones and bit rate scaled alike.
inline std::vector<float> PacketTrain(const ModemOptions& o, const std::vector<std::vector<std::uint8_t>>& payloads,
                                      double gap_s, double clock_error = 0.0) {
  ModemOptions sender = o;
  sender.mark_hz *= 1.0 + clock_error;
  sender.space_hz *= 1.0 + clock_error;
  sender.baud *= 1.0 + clock_error;
  const FskModulator mod(sender);
  return Train(payloads, static_cast<std::size_t>(gap_s * o.sample_rate), [&](const auto& p) { return mod.ModulatePacket(p); });
}

}  // namespace nava_modem::test_signals
