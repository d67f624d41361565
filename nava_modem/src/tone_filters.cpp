#include "nava_modem/tone_filters.h"

#include <cmath>

namespace nava_modem {
namespace {

// Running sums and the oscillator are renewed this often, so rounding cannot build up over
// hours of audio.
constexpr std::size_t kRenewEvery = 1 << 16;

}  // namespace

ToneFilters::ToneFilters(const ModemOptions& options)
    : window_(static_cast<int>(std::lround(SamplesPerBit(options)))), scale_(2.0 / window_) {
  const double freq[2] = {options.mark_hz, options.space_hz};
  for (int k = 0; k < 2; ++k) {
    tones_[k].rotation = std::polar(1.0, -2.0 * M_PI * freq[k] / options.sample_rate);
    tones_[k].oscillator = 1.0;
    tones_[k].terms.assign(window_, 0.0);
  }
}

double ToneFilters::Update(Tone& t, float sample) {
  const std::complex<double> term = t.oscillator * static_cast<double>(sample);
  t.sum += term - t.terms[at_];
  t.terms[at_] = term;
  t.oscillator *= t.rotation;
  if (pushed_ % kRenewEvery == 0) {
    t.oscillator /= std::abs(t.oscillator);
    t.sum = 0.0;
    for (const auto& v : t.terms) t.sum += v;
  }
  return std::abs(t.sum) * scale_;
}

void ToneFilters::Push(float sample) {
  ++pushed_;
  mark_ = Update(tones_[0], sample);
  space_ = Update(tones_[1], sample);
  at_ = at_ + 1 == static_cast<std::size_t>(window_) ? 0 : at_ + 1;
}

}  // namespace nava_modem
