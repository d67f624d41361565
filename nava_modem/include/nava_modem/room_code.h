#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "nava_modem/room_phy.h"

namespace nava_modem::room_code {

// A block of the `room` profile on the air: `info_bits` bits (bytes most significant bit first)
// through a convolutional code (K=9; rate 1/3 for today's packet, a header and the slowest
// payloads, rate 1/2 for the faster ones), scrambled, interleaved over `symbols` symbols so that
// the coded bits a symbol carries lie `symbols` / 4 or more trellis steps apart, and Gray-mapped
// onto 16 tones a sub-band, in `tones` sub-bands at once (BlockShape). Today's packet is the
// block of 48 bits over 42 one-tone symbols; a long frame's header and payload are blocks of
// their own (room_frame.h).
enum class Code { kThirdK9, kHalfK9 };
struct BlockShape {
  int tones = 1;  // sub-bands sounding at once in each symbol (1 to kBands)
  Code code = Code::kThirdK9;
};

constexpr int CodeRate(Code code) { return code == Code::kThirdK9 ? 3 : 2; }  // coded bits a trellis step
// Coded bits of a block of `info_bits` (the code's tail included).
constexpr int CodedBits(int info_bits, Code code = Code::kThirdK9) {
  return (info_bits + room_phy::kConstraint - 1) * CodeRate(code);
}
// The fewest symbols that carry them.
constexpr int BlockSymbols(int info_bits, BlockShape shape = {}) {
  const int per_symbol = room_phy::kBitsPerSymbol * shape.tones;
  return (CodedBits(info_bits, shape.code) + per_symbol - 1) / per_symbol;
}

// The tones (0..15) that carry the first `info_bits` bits of `bytes` over `symbols` symbols:
// `shape.tones` a symbol, symbol by symbol. Throws std::invalid_argument when the bytes hold
// fewer bits, the shape is impossible or the symbols cannot carry the coded block. Coded
// positions past the block carry the scrambler alone.
std::vector<int> EncodeBlock(const std::vector<std::uint8_t>& bytes, int info_bits, int symbols, BlockShape shape = {});

struct DecodedBlock {
  std::vector<std::uint8_t> bytes;  // (info_bits + 7) / 8, the last one's unused bits 0
  // Coded bits where the decoded codeword disagrees with the hard decisions: the errors the
  // code corrected, or a sign that the decision was noise when there are very many.
  int corrected = 0;
};
// The likeliest block (soft-decision Viterbi) from the soft decisions on every tone's coded bits
// in air order (symbol by symbol, tone by tone, the tone number's most significant bit first;
// > 0 means 1, the magnitude how sure, a log-likelihood ratio in nats): 4 a tone. Throws
// std::invalid_argument when they cannot hold the block.
DecodedBlock DecodeBlock(const std::vector<float>& soft, int info_bits, BlockShape shape = {});

// The coded bits of a symbol's tone (Gray code: neighbouring tones differ in one bit, so that
// a tone smeared into its neighbour costs one bit, not up to four).
int ToneBits(int tone);

// Today's 4-byte packet: the block of its 6 bytes (4 data bytes + CRC) over 42 symbols.
using Payload = std::array<std::uint8_t, room_phy::kPayloadBytes>;
using Tones = std::array<int, room_phy::kSymbols>;
using SoftBits = std::array<float, room_phy::kCodedBits>;
static_assert(CodedBits(room_phy::kPayloadBits) == room_phy::kCodedBits, "today's packet is a block");
static_assert(BlockSymbols(room_phy::kPayloadBits) == room_phy::kSymbols, "of 42 symbols");

Tones Encode(const Payload& payload);
struct Decoded {
  Payload payload{};
  int corrected = 0;
};
Decoded Decode(const SoftBits& soft);

}  // namespace nava_modem::room_code
