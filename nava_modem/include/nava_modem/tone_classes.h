#pragma once

// Bit decisions learnt from the packet itself: what each tone's filter shows when a MARK bit is
// sent and when a SPACE bit is, read off the frame's known bits (start, stop, header) and then
// its decided ones, in the log domain. No ROS.
//
// Why: in a real room the speaker's and the room's colouring can leave one tone 10 dB or more
// below the other, and what its filter shows with its tone off is then not a floor but the
// strong tone's leakage (its transitions, its smeared direct sound, its tail), about as loud as
// the weak tone itself. A decision that trusts both filters as the break's steady tones suggest
// (FskReceiver's Rician model) is then led by the weak tone's filter and fails although the
// strong tone alone tells every bit. Learning, per tone, how far apart the two kinds of bit lie
// against how much they spread (a linear discriminant of the log powers) weighs each filter by
// what it actually tells in this room.
#include <cstdint>

#include "nava_modem/frame.h"
#include "nava_modem/frame_repair.h"

namespace nava_modem {

struct ToneClassDecision {
  SoftFrame soft{};  // the frame's data bits: log-likelihood ratios of MARK over SPACE
  // Start and stop bits (of 14) the learnt discriminant decides against their known value: a
  // reading whose framing it cannot tell is not a packet (noise, or a wrong bit clock).
  int misframed = 0;
};

// heard[t][j]: tone t's (0 MARK, 1 SPACE) filter power at the end of frame bit j (0..69);
// `hard`: first decisions on the frame's bits (the known ones are taken as known). The
// discriminant is fitted on the known bits, then refitted on every bit as it decides them.
ToneClassDecision ToneClassSoft(const double heard[2][kFrameBits], const std::uint8_t* hard);

// The value a frame bit (0..69) is known to have (start 0, stop 1, the header's bits), or -1.
int KnownFrameBit(int j);

}  // namespace nava_modem
