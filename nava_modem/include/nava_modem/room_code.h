#pragma once

#include <array>
#include <cstdint>

#include "nava_modem/room_phy.h"

namespace nava_modem::room_code {

using Payload = std::array<std::uint8_t, room_phy::kPayloadBytes>;  // 4 data bytes + CRC
using Tones = std::array<int, room_phy::kSymbols>;                 // each symbol's tone, 0..15
// Soft decisions on the coded bits in air order (symbol by symbol, the tone number's most
// significant bit first): > 0 means 1, the magnitude how sure (a log-likelihood ratio, nats).
using SoftBits = std::array<float, room_phy::kCodedBits>;

// The tones that carry a payload: convolutional code, scrambler, interleaver, Gray mapping.
Tones Encode(const Payload& payload);

// The coded bits of a symbol's tone (Gray code: neighbouring tones differ in one bit, so that
// a tone smeared into its neighbour costs one bit, not up to four).
int ToneBits(int tone);

struct Decoded {
  Payload payload{};
  // Coded bits where the decoded codeword disagrees with the hard decisions: the errors the
  // code corrected, or a sign that the decision was noise when there are very many.
  int corrected = 0;
};
// The likeliest payload (soft-decision Viterbi over the whole packet).
Decoded Decode(const SoftBits& soft);

}  // namespace nava_modem::room_code
