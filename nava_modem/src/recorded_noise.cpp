#include "nava_modem/recorded_noise.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nava_modem/fft_plan.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {

Bands ListeningBands(Profile profile) {
  if (profile == Profile::kRoom) return {{room_phy::kLowestToneHz, room_phy::kHighestHz}};
  const ModemOptions modem;  // the thesis's tones, which the tables are measured with
  const double half = modem.baud / 2.0;
  return {{modem.mark_hz - half, modem.mark_hz + half}, {modem.space_hz - half, modem.space_hz + half}};
}

RecordedNoise::RecordedNoise(const std::vector<float>& samples, double sample_rate) : sample_rate_(sample_rate) {
  if (!(sample_rate > 0.0)) {
    throw std::invalid_argument("recorded noise: sample rate must be above 0 Hz, got " + std::to_string(sample_rate));
  }
  if (samples.size() < kWindow) {
    throw std::invalid_argument("recorded noise: expected at least " + std::to_string(kWindow) + " samples, got " +
                                std::to_string(samples.size()));
  }
  double sum = 0.0;
  for (float s : samples) {
    if (!std::isfinite(s)) throw std::invalid_argument("recorded noise: a sample is not a finite number");
    sum += static_cast<double>(s) * s;
  }
  power_ = sum / static_cast<double>(samples.size());
  if (!(power_ > 0.0)) throw std::invalid_argument("recorded noise: the recording is silent");

  FftPlan fft(FftKind::kRealToComplex, kWindow);
  std::vector<double> window(kWindow);
  const double pi = std::acos(-1.0);
  for (std::size_t k = 0; k < kWindow; ++k) window[k] = 0.5 - 0.5 * std::cos(2.0 * pi * k / kWindow);
  density_.assign(fft.output_length(), 0.0);
  for (std::size_t start = 0; start + kWindow <= samples.size(); start += kWindow / 2) {
    double* in = fft.real_input();
    for (std::size_t k = 0; k < kWindow; ++k) in[k] = window[k] * samples[start + k];
    fft.Execute();
    const std::complex<double>* out = fft.complex_output();
    for (std::size_t b = 0; b < density_.size(); ++b) density_[b] += std::norm(out[b]);
  }
  double total = 0.0;
  for (double d : density_) total += d;
  if (!(total > 0.0)) throw std::invalid_argument("recorded noise: the recording is silent");
  for (double& d : density_) d /= total;
}

double RecordedNoise::Fraction(const Bands& bands) const {
  const double bin_hz = sample_rate_ / kWindow;
  double fraction = 0.0;
  for (std::size_t b = 0; b < density_.size(); ++b) {
    // Bin b covers [(b - 1/2) bin_hz, (b + 1/2) bin_hz), clipped to [0, Nyquist].
    const double low = std::max(0.0, (b - 0.5) * bin_hz);
    const double high = std::min(sample_rate_ / 2.0, (b + 0.5) * bin_hz);
    if (high <= low) continue;
    double inside = 0.0;
    for (const auto& [lo, hi] : bands) inside += std::max(0.0, std::min(high, hi) - std::max(low, lo));
    fraction += density_[b] * std::min(1.0, inside / (high - low));
  }
  return fraction;
}

double WhiteFraction(const Bands& bands, double sample_rate) {
  const double nyquist = sample_rate / 2.0;
  double inside = 0.0;
  for (const auto& [lo, hi] : bands) inside += std::max(0.0, std::min(hi, nyquist) - std::max(lo, 0.0));
  return inside / nyquist;
}

double WhiteEquivalentOffsetDb(const RecordedNoise& noise, const Bands& bands, double white_rate) {
  // A recording with nothing in the bands is as harmless as white noise 60 dB down.
  const double recorded = std::max(noise.Fraction(bands), 1e-6 * WhiteFraction(bands, white_rate));
  return 10.0 * std::log10(WhiteFraction(bands, white_rate) / recorded);
}

}  // namespace nava_modem
