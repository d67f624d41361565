#pragma once

// One reading of a nava packet on one bit clock (the FSK receiver's frame reader gives it), and
// the acceptance step that turns a reading into a packet or a noise class. No ROS.
#include <array>
#include <cstdint>

#include "nava_modem/crc16.h"
#include "nava_modem/frame.h"
#include "nava_modem/frame_repair.h"
#include "nava_modem/packet_receiver.h"

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

// A packet when the reading's frame passes its CRC, repaired where that is trusted: first on
// each tone's level and floor read again from the frame's own bits (a room colours the break's
// steady tones), then on the break's model of the tones (one bit at most); repairs only on a
// clock within 1.5 % of the nominal rate, up to `max_fixed_bits` bits, and none where more than 2
// of the 14 start and stop bits are wrong. Else noise: zero_byte (no character framed), one_byte
// (no header) or bad_crc. The event carries the reading's times, level, quality and rate error.
RxEvent AcceptReading(const FrameReading& reading, CrcVariant crc, int max_fixed_bits);

}  // namespace nava_modem
