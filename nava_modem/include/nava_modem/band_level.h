#pragma once

#include "nava_modem/biquad.h"

namespace nava_modem {

// The level of a band of the signal, for carrier sense: a 2nd-order Butterworth high-pass and
// low-pass (biquads) at the band's edges, then the power smoothed over `seconds`. In dB of full
// scale: a full-scale tone inside the band reads 0 dB.
class BandLevel {
 public:
  BandLevel(double sample_rate, double low_hz, double high_hz, double seconds);

  void Push(float sample);
  double power() const { return 2.0 * power_; }  // a tone's mean square is half its peak's square
  double db() const;

 private:
  Biquad high_pass_, low_pass_;
  double smoothing_;  // per-sample weight of the newest power
  double power_ = 0.0;
};

}  // namespace nava_modem
