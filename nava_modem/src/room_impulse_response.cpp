#include "nava_modem/room_impulse_response.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>

#include "nava_modem/math_constants.h"
#include "nava_modem/noise_sources.h"
#include "nava_modem/real_fft.h"

namespace nava_modem {
namespace {

constexpr double kTailStartS = 0.005;
constexpr double kTailFadeS = 0.005;
constexpr double kEarlyFirstS = 0.005, kEarlyLastS = 0.040;
constexpr double kLn1000 = 6.907755278982137;  // 60 dB of amplitude decay

double Energy(const std::vector<double>& x) {
  double e = 0.0;
  for (double v : x) e += v * v;
  return e;
}

// The reflections on the sample grid (the nearest sample to each delay).
std::vector<double> EarlyReflections(std::size_t n, double rt60, double sample_rate, RandomSource& random) {
  std::vector<double> early(n, 0.0);
  for (const EarlyReflection& r : DrawEarlyReflections(rt60, random)) {
    const std::size_t i = std::min(n - 1, static_cast<std::size_t>(std::lround(r.delay_s * sample_rate)));
    early[i] += r.amplitude;
  }
  return early;
}

}  // namespace

std::vector<EarlyReflection> DrawEarlyReflections(double rt60, RandomSource& random) {
  double delay[kEarlyReflections], sign[kEarlyReflections], spread[kEarlyReflections];
  for (int r = 0; r < kEarlyReflections; ++r) {
    delay[r] = kEarlyFirstS + (kEarlyLastS - kEarlyFirstS) * random.Uniform();
    sign[r] = random.Uniform() < 0.5 ? -1.0 : 1.0;
    spread[r] = 0.4 + 0.6 * random.Uniform();
  }
  // Decay counted from the first reflection (the caller's scaling removes the factor), so that
  // however short rt60 is, that one does not underflow to zero.
  const double first = *std::min_element(delay, delay + kEarlyReflections);
  const double rate = kLn1000 / rt60;
  std::vector<EarlyReflection> reflections(kEarlyReflections);
  for (int r = 0; r < kEarlyReflections; ++r) {
    reflections[r].delay_s = delay[r];
    reflections[r].amplitude = sign[r] * spread[r] * std::exp(-rate * (delay[r] - first));
  }
  return reflections;
}

std::vector<double> BandedTail(std::size_t n, const std::vector<TailBand>& bands, double start_s, double fade_s,
                               double sample_rate, RandomSource& random) {
  if (bands.empty() || !(fade_s > 0.0) || !(start_s >= 0.0)) {
    throw std::invalid_argument("diffuse tail: expected at least one band, a fade above 0 s and a start at or after 0 s");
  }
  for (std::size_t b = 0; b < bands.size(); ++b) {
    if (!(bands[b].t60_s > 0.0) || (b > 0 && !(bands[b].top_hz > bands[b - 1].top_hz))) {
      throw std::invalid_argument("diffuse tail band " + std::to_string(b) + " (top " + std::to_string(bands[b].top_hz) +
                                  " Hz, T60 " + std::to_string(bands[b].t60_s) +
                                  " s): expected a T60 above 0 and tops ascending");
    }
  }
  const std::size_t size = FftSize(n);
  std::vector<double> noise(size);
  for (double& v : noise) v = random.Gaussian();
  const std::vector<std::complex<double>> spectrum = ForwardFft(noise, size);
  // Each band's noise (bins from the band before's top to its own), then its decay rate.
  std::vector<std::vector<double>> band_noise;
  std::vector<double> rate;
  double bottom = -1.0;
  for (const TailBand& band : bands) {
    std::vector<std::complex<double>> part(spectrum.size());
    for (std::size_t k = 0; k < spectrum.size(); ++k) {
      const double hz = BinHz(k, size, sample_rate);
      if (hz >= bottom && hz < band.top_hz) part[k] = spectrum[k];
    }
    band_noise.push_back(InverseFft(part, size));
    rate.push_back(kLn1000 / band.t60_s);
    bottom = band.top_hz;
  }
  std::vector<double> tail(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / sample_rate;
    if (t < start_s) continue;
    const double fade = t < start_s + fade_s ? 0.5 - 0.5 * std::cos(kPi * (t - start_s) / fade_s) : 1.0;
    // Decay counted from the tail's start, not from 0: the same shape up to a factor (which the
    // caller's scaling removes), and no underflow to zero for very short decays.
    const double since = t - start_s;
    double sum = 0.0;
    for (std::size_t b = 0; b < bands.size(); ++b) sum += band_noise[b][i] * std::exp(-rate[b] * since);
    tail[i] = fade * sum;
  }
  return tail;
}

// Gaussian noise of length n split at the crossover into (below, above), each band then given
// its own exponential decay, starting at kTailStartS with a raised-cosine fade-in.
std::vector<double> DiffuseTail(std::size_t n, double rt60, double sample_rate, RandomSource& random) {
  const double infinity = std::numeric_limits<double>::infinity();
  return BandedTail(n, {{kRoomCrossoverHz, rt60}, {infinity, kHighBandDecayRatio * rt60}}, kTailStartS, kTailFadeS,
                    sample_rate, random);
}

void ValidateRoomResponseArguments(double rt60, double drr_db, double sample_rate) {
  if (!(sample_rate > 0.0) || !std::isfinite(sample_rate)) {
    throw std::invalid_argument("sample rate " + std::to_string(sample_rate) + " Hz: expected above 0");
  }
  if (!(rt60 >= 0.0 && rt60 <= 10.0)) {
    throw std::invalid_argument("rt60 " + std::to_string(rt60) + " s: expected 0 (no room) or above 0 and at most 10");
  }
  if (!(std::fabs(drr_db) <= 40.0)) {
    throw std::invalid_argument("drr_db " + std::to_string(drr_db) + " dB: expected from -40 to 40");
  }
}

std::vector<float> RoomImpulseResponse(double rt60, double drr_db, double sample_rate, std::uint32_t seed) {
  ValidateRoomResponseArguments(rt60, drr_db, sample_rate);
  if (rt60 == 0.0) return {1.0f};

  const std::size_t n = RoomResponseSamples(rt60, sample_rate);
  RandomSource random(seed, kImpulseResponseStream);
  std::vector<double> early = EarlyReflections(n, rt60, sample_rate, random);
  std::vector<double> tail = DiffuseTail(n, rt60, sample_rate, random);
  early[0] = tail[0] = 0.0;  // index 0 is the direct sound's alone

  // Early and tail each to their share, then the sum (whose cross terms are not quite zero)
  // to the asked ratio exactly: direct energy is 1, so the reverberant energy is 10^(-drr/10).
  const double reverberant = std::pow(10.0, -drr_db / 10.0);
  // (A guard for absurdly low sample rates, where a part may land wholly on index 0.)
  const double early_gain = Energy(early) > 0.0 ? std::sqrt(kEarlyShare / Energy(early)) : 0.0;
  const double tail_gain = Energy(tail) > 0.0 ? std::sqrt((1.0 - kEarlyShare) / Energy(tail)) : 0.0;
  std::vector<double> sum(n);
  for (std::size_t i = 0; i < n; ++i) sum[i] = early_gain * early[i] + tail_gain * tail[i];
  const double gain = Energy(sum) > 0.0 ? std::sqrt(reverberant / Energy(sum)) : 0.0;
  std::vector<float> response(n);
  response[0] = 1.0f;
  for (std::size_t i = 1; i < n; ++i) response[i] = static_cast<float>(gain * sum[i]);
  return response;
}

std::size_t RoomResponseSamples(double rt60, double sample_rate) {
  return static_cast<std::size_t>(std::ceil(std::max(1.2 * rt60, 0.045) * sample_rate));
}

double MeasureDrrDb(const std::vector<float>& response) {
  if (response.empty()) return std::numeric_limits<double>::quiet_NaN();
  double rest = 0.0;
  for (std::size_t i = 1; i < response.size(); ++i) rest += static_cast<double>(response[i]) * response[i];
  if (rest <= 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(static_cast<double>(response[0]) * response[0] / rest);
}

}  // namespace nava_modem
