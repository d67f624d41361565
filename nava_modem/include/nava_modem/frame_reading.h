#pragma once

// One reading of a nava packet on one bit clock (the FSK receiver's frame reader gives it), and
// the acceptance step that turns a reading into a packet or a noise class. No ROS.
#include <array>
#include <cstdint>

#include "nava_modem/clock_search.h"
#include "nava_modem/crc16.h"
#include "nava_modem/frame.h"
#include "nava_modem/frame_repair.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/tone_model.h"
#include "nava_modem/tone_ring.h"

namespace nava_modem {

struct FrameReading {
  // The filter step each bit of the packet was read at, the break's first SPACE bit first.
  std::array<std::int64_t, kPacketBits> at{};
  std::array<std::uint8_t, kFrameBits> hard{};  // the first decision on each bit of the frame
  SoftFrame soft{};  // the data bits' log-likelihood ratios on the break's model of the tones
  std::array<std::array<double, kFrameBits>, 2> heard{};  // MARK's and SPACE's power at each frame bit
  double start = 0.0, end = 0.0;  // s: where the break began and the frame ended
  double level_db = 0.0;          // the frame's mean in-band power, dB of full scale
  double quality = 0.0;           // the tone filters' outputs summed, over the frame's bits
  double rate_error = 0.0;        // the clock read on: the sender's rate over the nominal, less 1
};

// What the frame reader reads from: the tone filters' outputs, the packet's tone model, the
// tones normalised by it (the bit clock's loop follows their zero crossings), the filters' window
// and filter steps a bit (the nominal rate), and seconds a filter step.
struct FrameSource {
  const ToneRing& ring;
  const ToneModel& model;
  const NormalizedTones& tones;
  int window;
  double per_bit;
  double seconds_per_step;
};

// The frame reader: the frame read on the bit clock that starts at filter step `first_mark` (the
// break's first MARK bit), `period` steps a bit, which a digital PLL (BitClock) then follows
// through the data's clear transitions; each bit decided by its log-likelihood ratio against
// each tone's level and floor plus the tail the room keeps of the bits before (tone model).
FrameReading ReadFrame(const FrameSource& source, double first_mark, double period);

// A packet when the reading's frame passes its CRC, repaired where that is trusted: first on
// each tone's level and floor read again from the frame's own bits (a room colours the break's
// steady tones), then on the break's model of the tones (one bit at most); repairs only on a
// clock within 1.5 % of the nominal rate, up to `max_fixed_bits` bits, and none where more than 2
// of the 14 start and stop bits are wrong. Else noise: zero_byte (no character framed), one_byte
// (no header) or bad_crc. The event carries the reading's times, level, quality and rate error.
RxEvent AcceptReading(const FrameReading& reading, CrcVariant crc, int max_fixed_bits);

}  // namespace nava_modem
