#pragma once

namespace nava_modem {

// A digital phase-locked loop for the bit clock. Bit k starts at start(k) and lasts `period`
// samples; the one-bit tone filters are aligned with it at its last sample. Where two bits
// differ, the filters' difference crosses zero half a filter window after the boundary; each
// such crossing seen pulls the phase by `phase_gain` of its error and the period by
// `period_gain` of it. The clock is anchored at the last boundary seen, so that a period
// correction moves the bits ahead, never those behind.
class BitClock {
 public:
  BitClock(double start_of_bit_zero, double period, double window, double phase_gain, double period_gain)
      : anchor_time_(start_of_bit_zero), period_(period), half_window_(window / 2.0),
        phase_gain_(phase_gain), period_gain_(period_gain) {}

  double Start(int k) const { return anchor_time_ + (k - anchor_bit_) * period_; }
  double AlignedSample(int k) const { return Start(k) + period_ - 1.0; }
  // Where the crossing for a transition into bit k is expected.
  double ExpectedCrossing(int k) const { return Start(k) + half_window_ - 1.0; }
  // A crossing for a transition into bit k was seen at `sample`.
  void Observe(int k, double sample) {
    const double error = sample - ExpectedCrossing(k);
    anchor_time_ = Start(k) + phase_gain_ * error;
    anchor_bit_ = k;
    period_ += period_gain_ * error;
  }
  double period() const { return period_; }

 private:
  double anchor_time_;
  int anchor_bit_ = 0;
  double period_, half_window_, phase_gain_, period_gain_;
};

}  // namespace nava_modem
