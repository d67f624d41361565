#pragma once

#include <array>
#include <optional>
#include <vector>

#include "nava_modem/frame.h"

namespace nava_modem {

constexpr int kFrameDataBits = kFrameBytes * 8;  // the bits the CRC and header check: 56

// Soft decisions on a frame's 56 data bits in air order (byte by byte, LSB first): the sign is
// the bit (> 0 is 1), the magnitude how sure the demodulator is.
using SoftFrame = std::array<float, kFrameDataBits>;

struct RepairedFrame {
  Frame frame;
  int fixed_bits = 0;  // bits flipped to make header and CRC right
};

// The frame the soft decisions spell, when its header is 0x55 and its CRC matches; otherwise
// the likeliest frame that does after flipping one of the 8 least sure bits or two of the 5
// least sure (likeliest: the smallest total certainty flipped), if `max_fixed_bits` allows.
// The 8 header bits and 16 CRC bits make each of the 18 candidates a 1 in 16 million chance of
// passing a wrong frame (where the header was decided freely; see FskReceiver::Equalize).
// How often repairs pass wrong frames was measured, 64 times faster than by waiting for wrong
// packets, by counting the candidates that would pass if the CRC were off by each of 64 fixed
// 16-bit patterns: a frame of noise lands on any of them as readily as on the right CRC.
std::optional<RepairedFrame> RepairFrame(const SoftFrame& soft, CrcVariant crc, int max_fixed_bits);

// The frame `soft` spells with the bits of one error event flipped together (events: each a list
// of data-bit indices, byte * 8 + bit, weakest first, as a sequence search weighed them; see
// FskEqualizer), when header and CRC then match. Only events of 2 to `max_event_bits` bits count
// (single bits are RepairFrame's), and only the first `max_events` of them: each is one more
// candidate for the check bits.
// Throws std::invalid_argument for an index outside 0-55 or one named twice in an event.
std::optional<RepairedFrame> RepairEvent(const SoftFrame& soft, const std::vector<std::vector<int>>& events,
                                         CrcVariant crc, int max_events, int max_event_bits);

// The hard decisions as bytes.
Frame HardFrame(const SoftFrame& soft);

}  // namespace nava_modem
