#pragma once

// What the break before a nava packet tells of how each tone arrives: each tone's direct level
// and noise floor, and the room's reverberant tail, so that the bits are decided on each tone's
// energy against its own level and its own tail (the FSK receiver's second stage, after the break
// detector). No ROS.
#include "nava_modem/tone_ring.h"

namespace nava_modem {

struct ToneModel {
  double level[2] = {1.0, 1.0};  // direct power of MARK, SPACE in its own filter
  double floor[2] = {0.0, 0.0};  // the filter's power with its tone absent and no tail
  double decay = 0.0;            // the tail's power kept from one bit to the next
  double gain = 0.0;             // tail power a bit of a tone adds, over its direct power
  double tail[2] = {0.0, 0.0};   // each tone's tail at the first bit of the frame
};

// The model read from the break whose SPACE-to-MARK step lies at filter step `break_step`, with
// `per_bit` filter steps a bit, on the detector's clock. With SPACE off in the MARK half, the
// SPACE filter shows the room's tail of the SPACE bits decaying, plus its floor: three group means
// give the decay per bit, the tail at the step and the floor (no tail where they do not fall
// clearly); the tails that build up over each half are taken off the tones' levels.
ToneModel FitToneModel(const ToneRing& ring, double break_step, double per_bit);

}  // namespace nava_modem
