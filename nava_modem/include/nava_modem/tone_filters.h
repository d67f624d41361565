#pragma once

#include <vector>

#include "nava_modem/modem_options.h"

namespace nava_modem {

// The demodulator's two band-pass filters: for each of MARK and SPACE, the correlation of the
// last bit's worth of samples with the tone (a sliding DFT bin, the filter matched to one bit
// of that tone). Outputs are squared amplitudes: a full-scale tone gives 1 in its own filter.
// The window slides by `step` samples at a time (Step(), about a 40th of a bit), which keeps
// the timing fine enough and halves the work per sample.
class ToneFilters {
 public:
  explicit ToneFilters(const ModemOptions& options);

  // Samples per output: a 40th of a bit, at least 1.
  static int Step(const ModemOptions& options);

  // Feeds one sample; true when a new output is ready (every step-th sample), describing the
  // window ending with this sample.
  bool Push(float sample);

  // Squared outputs (the demodulator works on powers; no square roots per sample).
  double mark_power() const { return mark_power_; }
  double space_power() const { return space_power_; }
  // The outputs as complex amplitudes (real, imaginary), on the same scale: the correlation with
  // e^{-j w n}, n counted from the first sample, so that a steady tone keeps its phase from one
  // output to the next (the equaliser, fsk_equalizer.h, models the room on them).
  double mark_re() const { return tones_[0].sum_re * scale_; }
  double mark_im() const { return tones_[0].sum_im * scale_; }
  double space_re() const { return tones_[1].sum_re * scale_; }
  double space_im() const { return tones_[1].sum_im * scale_; }
  int window() const { return window_; }  // in steps
  int step() const { return step_; }

 private:
  // Complex values kept as pairs of doubles: std::complex's multiplication checks for
  // infinities on every call, which costs more than the rest of the filter.
  struct Tone {
    double rot_re, rot_im;  // e^{-j w} per sample
    double osc_re = 1.0, osc_im = 0.0;  // e^{-j w n}
    double sum_re = 0.0, sum_im = 0.0;
    double block_re = 0.0, block_im = 0.0;  // the current step's terms
    std::vector<double> terms;  // the window's steps, a ring of (re, im)
  };
  double Slide(Tone& t);

  int step_;
  int window_;
  int filled_ = 0;  // samples in the current step
  double scale_, scale2_;  // output to amplitude, squared output to squared amplitude
  std::size_t at_ = 0;  // ring position
  std::size_t pushed_ = 0;
  Tone tones_[2];
  double mark_power_ = 0.0, space_power_ = 0.0;
};

}  // namespace nava_modem
