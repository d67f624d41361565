#include "nava_modem/room_code.h"

#include <algorithm>
#include <cmath>
#include <memory>

extern "C" {
#include <fec.h>
}

namespace nava_modem::room_code {
namespace {

using room_phy::kCodedBits;
using room_phy::kPayloadBits;
using room_phy::kSymbols;

constexpr int kSteps = kPayloadBits + room_phy::kConstraint - 1;  // trellis steps, tail included
constexpr int kPolys[room_phy::kCodeRate] = {V39POLYA, V39POLYB, V39POLYC};
// libfec takes soft bits as 0 (sure 0) .. 255 (sure 1); a log-likelihood ratio of 4 nats (a
// clear tone) maps to about 100 steps from the middle.
constexpr float kSoftScale = 25.0f;

// The scrambler's bits: a maximal-length sequence (x^9 + x^5 + 1), so that a payload of
// repeated bytes does not send the same tone over and over.
const std::array<std::uint8_t, kCodedBits>& Scrambler() {
  static const std::array<std::uint8_t, kCodedBits> bits = [] {
    std::array<std::uint8_t, kCodedBits> out{};
    unsigned state = 0x1FF;
    for (int k = 0; k < kCodedBits; ++k) {
      const unsigned bit = ((state >> 8) ^ (state >> 4)) & 1u;
      out[k] = static_cast<std::uint8_t>(bit);
      state = ((state << 1) | bit) & 0x1FF;
    }
    return out;
  }();
  return bits;
}

// Coded bit k (in code order) goes out in symbol k % 42, as that symbol's bit k / 42.
int AirIndex(int k) { return (k % kSymbols) * room_phy::kBitsPerSymbol + k / kSymbols; }

// The convolutional code's output, in code order, before scrambling.
std::array<std::uint8_t, kCodedBits> Convolve(const Payload& payload) {
  std::array<std::uint8_t, kCodedBits> out{};
  int state = 0;
  for (int i = 0; i < kSteps; ++i) {
    const int bit = i < kPayloadBits ? (payload[i / 8] >> (7 - i % 8)) & 1 : 0;
    state = ((state << 1) | bit) & ((1 << room_phy::kConstraint) - 1);  // the encoder remembers K bits
    for (int p = 0; p < room_phy::kCodeRate; ++p) out[room_phy::kCodeRate * i + p] = static_cast<std::uint8_t>(parity(state & kPolys[p]));
  }
  return out;
}

struct ViterbiDeleter {
  void operator()(void* v) const { delete_viterbi39(v); }
};

}  // namespace

int ToneBits(int tone) { return tone ^ (tone >> 1); }  // the tone number's Gray code

Tones Encode(const Payload& payload) {
  const auto coded = Convolve(payload);
  const auto& scrambler = Scrambler();
  std::array<int, kCodedBits> air{};
  for (int k = 0; k < kCodedBits; ++k) air[AirIndex(k)] = coded[k] ^ scrambler[k];
  Tones tones{};
  for (int s = 0; s < kSymbols; ++s) {
    int value = 0;
    for (int j = 0; j < room_phy::kBitsPerSymbol; ++j) value = (value << 1) | air[s * room_phy::kBitsPerSymbol + j];
    // The tone whose Gray code the bits are.
    int tone = value;
    for (int shift = 1; shift < room_phy::kBitsPerSymbol; shift <<= 1) tone ^= tone >> shift;
    tones[s] = tone;
  }
  return tones;
}

Decoded Decode(const SoftBits& soft) {
  const auto& scrambler = Scrambler();
  std::array<unsigned char, kCodedBits> symbols{};
  std::array<float, kCodedBits> llr{};
  for (int k = 0; k < kCodedBits; ++k) {
    llr[k] = scrambler[k] ? -soft[AirIndex(k)] : soft[AirIndex(k)];
    symbols[k] = static_cast<unsigned char>(std::clamp(std::lround(127.5f + kSoftScale * llr[k]), 0L, 255L));
  }
  // libfec keeps the decoder's state in a heap object; one per call keeps Decode pure and
  // thread-safe (it costs microseconds against a packet's 1.9 s).
  std::unique_ptr<void, ViterbiDeleter> viterbi(create_viterbi39(kPayloadBits));
  init_viterbi39(viterbi.get(), 0);
  update_viterbi39_blk(viterbi.get(), symbols.data(), kSteps);
  Decoded out;
  chainback_viterbi39(viterbi.get(), out.payload.data(), kPayloadBits, 0);
  const auto coded = Convolve(out.payload);
  for (int k = 0; k < kCodedBits; ++k) out.corrected += (llr[k] > 0.0f) != (coded[k] != 0);
  return out;
}

}  // namespace nava_modem::room_code
