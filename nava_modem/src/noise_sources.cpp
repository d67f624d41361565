#include "nava_modem/noise_sources.h"

#include <cmath>
#include <complex>

#include "nava_modem/math_constants.h"
#include "nava_modem/real_fft.h"

namespace nava_modem {
namespace {

// Scales x to mean power 1 (unless it is silent).
void NormalisePower(std::vector<double>& x) {
  double sum = 0.0;
  for (double v : x) sum += v * v;
  if (sum <= 0.0) return;
  const double g = 1.0 / std::sqrt(sum / static_cast<double>(x.size()));
  for (double& v : x) v *= g;
}

}  // namespace

RandomSource::RandomSource(std::uint32_t seed, std::uint32_t stream) {
  std::seed_seq seq{seed, stream};
  engine_.seed(seq);
}

double RandomSource::Uniform() { return (static_cast<double>(engine_()) + 0.5) / 4294967296.0; }

double RandomSource::Gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double r = std::sqrt(-2.0 * std::log(Uniform()));
  const double a = kTwoPi * Uniform();
  spare_ = r * std::sin(a);
  has_spare_ = true;
  return r * std::cos(a);
}

std::vector<double> WhiteNoise(std::size_t n, std::uint32_t seed) {
  RandomSource random(seed, kNoiseStream);
  std::vector<double> x(n);
  for (double& v : x) v = random.Gaussian();
  return x;
}

std::vector<double> PinkNoise(std::size_t n, double sample_rate, std::uint32_t seed) {
  if (n == 0) return {};
  const std::size_t size = FftSize(n);
  std::vector<std::complex<double>> spectrum = ForwardFft(WhiteNoise(size, seed), size);
  constexpr double kFloorHz = 20.0;
  spectrum[0] = 0.0;
  for (std::size_t k = 1; k < spectrum.size(); ++k) {
    spectrum[k] /= std::sqrt(std::max(BinHz(k, size, sample_rate), kFloorHz));
  }
  std::vector<double> x = InverseFft(spectrum, size);
  x.resize(n);
  NormalisePower(x);
  return x;
}

std::vector<double> MotorWhine(std::size_t n, double sample_rate, double hz, double am_hz, std::uint32_t seed) {
  RandomSource random(seed, kWhineStream);
  // The wander: three slow sines whose amplitudes add up to 1 %.
  constexpr double kWander = 0.01;
  const double wander_hz[3] = {0.13, 0.31, 0.67};
  const double wander_share[3] = {0.5, 0.3, 0.2};
  double wander_phase[3];
  for (double& p : wander_phase) p = kTwoPi * random.Uniform();
  const double am_phase = kTwoPi * random.Uniform();
  const double nyquist = sample_rate / 2.0;
  const double harmonic_amplitude[3] = {1.0, 0.5, 0.25};

  std::vector<double> x(n);
  double phase = kTwoPi * random.Uniform();  // of the fundamental; harmonic h runs at h x phase
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / sample_rate;
    double wander = 0.0;
    for (int k = 0; k < 3; ++k) wander += wander_share[k] * std::sin(kTwoPi * wander_hz[k] * t + wander_phase[k]);
    const double f = hz * (1.0 + kWander * wander);
    double v = 0.0;
    for (int h = 1; h <= 3; ++h) {
      if (h * hz * (1.0 + kWander) >= nyquist) break;
      v += harmonic_amplitude[h - 1] * std::sin(h * phase);
    }
    const double envelope = am_hz > 0.0 ? 1.0 + 0.5 * std::sin(kTwoPi * am_hz * t + am_phase) : 1.0;
    x[i] = envelope * v;
    phase = std::fmod(phase + kTwoPi * f / sample_rate, kTwoPi);
  }
  NormalisePower(x);
  return x;
}

}  // namespace nava_modem
