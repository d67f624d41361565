#pragma once

// The nava receiver's first stage: where a packet's break turns from SPACE to MARK. Over two
// windows of the tone filters' outputs, the last `window` steps and the `window` before them, it
// reads how much the later is MARK and the earlier SPACE (each from -1 to 1, the smaller of the
// two: the edge of a burst, with tones on one side only, is no step), both from the tones summed
// and with each tone on its own scale (a room and a speaker can leave MARK 10 dB or more below
// SPACE, and SPACE's reverberant tail then outweighs MARK's direct sound in the sums), and takes
// the clearer. No ROS.
#include <cstdint>

#include "nava_modem/tone_ring.h"

namespace nava_modem {

class BreakDetector {
 public:
  // `window`: filter steps in each half (above 0, else std::invalid_argument).
  explicit BreakDetector(std::int64_t window);
  // Takes in step n of `ring` (steps come in order, each once, the ring holding the last two
  // windows).
  void Update(const ToneRing& ring, std::int64_t n);
  // How clearly the windows straddle a SPACE-to-MARK step, from -1 to 1; meaningful once two
  // windows are in.
  double Step() const;
  // The two windows' power, summed.
  double power() const { return after_power_ + before_power_; }
  std::int64_t window() const { return window_; }

 private:
  std::int64_t window_;
  // Running sums of MARK less SPACE and of the two summed, over the later window and the earlier.
  double after_ = 0.0, before_ = 0.0, after_power_ = 0.0, before_power_ = 0.0;
};

}  // namespace nava_modem
