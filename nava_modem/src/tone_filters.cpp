#include "nava_modem/tone_filters.h"

#include <algorithm>
#include <cmath>

namespace nava_modem {
namespace {

// Running sums and the oscillators are renewed this often (in steps), so rounding cannot
// build up over hours of audio.
constexpr std::size_t kRenewEvery = 1 << 16;

}  // namespace

int ToneFilters::Step(const ModemOptions& options) {
  return std::max(1, static_cast<int>(SamplesPerBit(options) / 40.0));
}

ToneFilters::ToneFilters(const ModemOptions& options)
    : step_(Step(options)), window_(static_cast<int>(std::lround(SamplesPerBit(options) / step_))) {
  scale_ = 2.0 / (window_ * step_);
  scale2_ = scale_ * scale_;
  const double freq[2] = {options.mark_hz, options.space_hz};
  for (int k = 0; k < 2; ++k) {
    const double w = 2.0 * M_PI * freq[k] / options.sample_rate;
    tones_[k].rot_re = std::cos(w);
    tones_[k].rot_im = -std::sin(w);
    tones_[k].terms.assign(2 * static_cast<std::size_t>(window_), 0.0);
  }
}

double ToneFilters::Slide(Tone& t) {
  double* old = &t.terms[2 * at_];
  t.sum_re += t.block_re - old[0];
  t.sum_im += t.block_im - old[1];
  old[0] = t.block_re;
  old[1] = t.block_im;
  t.block_re = t.block_im = 0.0;
  if (pushed_ % kRenewEvery == 0) {
    const double norm = std::sqrt(t.osc_re * t.osc_re + t.osc_im * t.osc_im);
    t.osc_re /= norm;
    t.osc_im /= norm;
    t.sum_re = t.sum_im = 0.0;
    for (std::size_t k = 0; k < t.terms.size(); k += 2) {
      t.sum_re += t.terms[k];
      t.sum_im += t.terms[k + 1];
    }
  }
  return (t.sum_re * t.sum_re + t.sum_im * t.sum_im) * scale2_;
}

bool ToneFilters::Push(float sample) {
  for (Tone& t : tones_) {
    t.block_re += t.osc_re * sample;
    t.block_im += t.osc_im * sample;
    const double o_re = t.osc_re * t.rot_re - t.osc_im * t.rot_im;
    t.osc_im = t.osc_re * t.rot_im + t.osc_im * t.rot_re;
    t.osc_re = o_re;
  }
  if (++filled_ < step_) return false;
  filled_ = 0;
  ++pushed_;
  mark_power_ = Slide(tones_[0]);
  space_power_ = Slide(tones_[1]);
  at_ = at_ + 1 == static_cast<std::size_t>(window_) ? 0 : at_ + 1;
  return true;
}

}  // namespace nava_modem
