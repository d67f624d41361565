#pragma once

#include <complex>
#include <vector>

#include "nava_modem/modem_options.h"

namespace nava_modem {

// The demodulator's two band-pass filters: for each of MARK and SPACE, the correlation of the
// last bit's worth of samples with the tone (a sliding DFT bin, the filter matched to one bit
// of that tone). Outputs are amplitudes: a full-scale tone gives 1 in its own filter.
class ToneFilters {
 public:
  explicit ToneFilters(const ModemOptions& options);

  // Feeds one sample; mark() and space() then describe the window ending with it.
  void Push(float sample);

  double mark() const { return mark_; }
  double space() const { return space_; }
  int window() const { return window_; }

 private:
  struct Tone {
    std::complex<double> rotation;    // e^{-j w} per sample
    std::complex<double> oscillator;  // e^{-j w n}
    std::complex<double> sum;
    std::vector<std::complex<double>> terms;  // the window's terms, a ring
  };
  double Update(Tone& t, float sample);

  int window_;
  double scale_;  // to amplitude
  std::size_t at_ = 0;  // ring position
  std::size_t pushed_ = 0;
  Tone tones_[2];
  double mark_ = 0.0, space_ = 0.0;
};

}  // namespace nava_modem
