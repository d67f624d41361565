#include "nava_modem/room_code.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

extern "C" {
#include <fec.h>
}

namespace nava_modem::room_code {
namespace {

using room_phy::kBitsPerSymbol;
using room_phy::kConstraint;

constexpr int kThirdPolys[3] = {V39POLYA, V39POLYB, V39POLYC};
constexpr int kHalfPolys[2] = {V29POLYA, V29POLYB};
// libfec takes soft bits as 0 (sure 0) .. 255 (sure 1); a log-likelihood ratio of 4 nats (a
// clear tone) maps to about 100 steps from the middle.
constexpr float kSoftScale = 25.0f;

// The scrambler's first `count` bits: a maximal-length sequence (x^9 + x^5 + 1, period 511),
// so that a payload of repeated bytes does not send the same tone over and over.
std::vector<std::uint8_t> Scrambler(int count) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(count));
  unsigned state = 0x1FF;
  for (auto& bit : out) {
    bit = static_cast<std::uint8_t>(((state >> 8) ^ (state >> 4)) & 1u);
    state = ((state << 1) | bit) & 0x1FF;
  }
  return out;
}

// Coded bit k (in code order) goes out in symbol k % symbols, as that symbol's bit k / symbols
// (of `per_symbol`).
int AirIndex(int k, int symbols, int per_symbol) { return (k % symbols) * per_symbol + k / symbols; }

// The convolutional code's output, in code order, before scrambling.
std::vector<std::uint8_t> Convolve(const std::vector<std::uint8_t>& bytes, int info_bits, Code code) {
  const int steps = info_bits + kConstraint - 1;  // the tail brings the encoder back to 0
  const int rate = CodeRate(code);
  const int* polys = code == Code::kThirdK9 ? kThirdPolys : kHalfPolys;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(steps) * rate);
  int state = 0;
  for (int i = 0; i < steps; ++i) {
    const int bit = i < info_bits ? (bytes[static_cast<std::size_t>(i / 8)] >> (7 - i % 8)) & 1 : 0;
    state = ((state << 1) | bit) & ((1 << kConstraint) - 1);  // the encoder remembers K bits
    for (int p = 0; p < rate; ++p) out[static_cast<std::size_t>(rate * i + p)] = static_cast<std::uint8_t>(parity(state & polys[p]));
  }
  return out;
}

// libfec's Viterbi decoder for a code, behind one face: it keeps its state in a heap object; one
// per block keeps DecodeBlock pure and thread-safe (it costs microseconds against a frame's seconds).
class Viterbi {
 public:
  Viterbi(Code code, int info_bits) : code_(code) {
    state_ = code == Code::kThirdK9 ? create_viterbi39(info_bits) : create_viterbi29(info_bits);
    code == Code::kThirdK9 ? init_viterbi39(state_, 0) : init_viterbi29(state_, 0);
  }
  ~Viterbi() { code_ == Code::kThirdK9 ? delete_viterbi39(state_) : delete_viterbi29(state_); }
  Viterbi(const Viterbi&) = delete;
  Viterbi& operator=(const Viterbi&) = delete;
  void Update(unsigned char* levels, int steps) {
    code_ == Code::kThirdK9 ? update_viterbi39_blk(state_, levels, steps) : update_viterbi29_blk(state_, levels, steps);
  }
  void Chainback(std::uint8_t* data, int info_bits) {
    const unsigned n = static_cast<unsigned>(info_bits);
    code_ == Code::kThirdK9 ? chainback_viterbi39(state_, data, n, 0) : chainback_viterbi29(state_, data, n, 0);
  }

 private:
  Code code_;
  void* state_;
};

void CheckBlock(int info_bits, int symbols, BlockShape shape, const char* what) {
  if (shape.tones < 1 || shape.tones > room_phy::kBands) {
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(shape.tones) + " tones a symbol, expected 1 to " +
                                std::to_string(room_phy::kBands));
  }
  if (info_bits < 1 || CodedBits(info_bits, shape.code) > symbols * kBitsPerSymbol * shape.tones) {
    throw std::invalid_argument(std::string(what) + ": a block of " + std::to_string(info_bits) + " bits does not fit " +
                                std::to_string(symbols) + " symbols (" + std::to_string(BlockSymbols(info_bits, shape)) +
                                " needed)");
  }
}

}  // namespace

int ToneBits(int tone) { return tone ^ (tone >> 1); }  // the tone number's Gray code

std::vector<int> EncodeBlock(const std::vector<std::uint8_t>& bytes, int info_bits, int symbols, BlockShape shape) {
  CheckBlock(info_bits, symbols, shape, "room_code::EncodeBlock");
  if (bytes.size() * 8 < static_cast<std::size_t>(info_bits)) {
    throw std::invalid_argument("room_code::EncodeBlock: " + std::to_string(bytes.size()) + " bytes hold fewer than " +
                                std::to_string(info_bits) + " bits");
  }
  const int per_symbol = kBitsPerSymbol * shape.tones;
  const int air_bits = symbols * per_symbol;
  const auto coded = Convolve(bytes, info_bits, shape.code);
  const auto scrambler = Scrambler(air_bits);
  std::vector<int> air(static_cast<std::size_t>(air_bits));
  for (int k = 0; k < air_bits; ++k) {
    const int bit = k < static_cast<int>(coded.size()) ? coded[static_cast<std::size_t>(k)] : 0;
    air[static_cast<std::size_t>(AirIndex(k, symbols, per_symbol))] = bit ^ scrambler[static_cast<std::size_t>(k)];
  }
  std::vector<int> tones(static_cast<std::size_t>(symbols * shape.tones));
  for (std::size_t t = 0; t < tones.size(); ++t) {
    int value = 0;
    for (int j = 0; j < kBitsPerSymbol; ++j) value = (value << 1) | air[t * kBitsPerSymbol + static_cast<std::size_t>(j)];
    // The tone whose Gray code the bits are.
    int tone = value;
    for (int shift = 1; shift < kBitsPerSymbol; shift <<= 1) tone ^= tone >> shift;
    tones[t] = tone;
  }
  return tones;
}

DecodedBlock DecodeBlock(const std::vector<float>& soft, int info_bits, BlockShape shape) {
  const int per_symbol = kBitsPerSymbol * std::max(1, shape.tones);
  const int symbols = static_cast<int>(soft.size()) / per_symbol;
  CheckBlock(info_bits, symbols, shape, "room_code::DecodeBlock");
  const int coded_bits = CodedBits(info_bits, shape.code);
  const auto scrambler = Scrambler(coded_bits);
  std::vector<unsigned char> levels(static_cast<std::size_t>(coded_bits));
  std::vector<float> llr(static_cast<std::size_t>(coded_bits));
  for (int k = 0; k < coded_bits; ++k) {
    const float s = soft[static_cast<std::size_t>(AirIndex(k, symbols, per_symbol))];
    llr[static_cast<std::size_t>(k)] = scrambler[static_cast<std::size_t>(k)] ? -s : s;
    levels[static_cast<std::size_t>(k)] =
        static_cast<unsigned char>(std::clamp(std::lround(127.5f + kSoftScale * llr[static_cast<std::size_t>(k)]), 0L, 255L));
  }
  Viterbi viterbi(shape.code, info_bits);
  viterbi.Update(levels.data(), info_bits + kConstraint - 1);
  DecodedBlock out;
  // (A spare byte: chainback's writes stay within the bytes the bits fill, but cost nothing to guard.)
  std::vector<std::uint8_t> decoded(static_cast<std::size_t>((info_bits + 7) / 8 + 1), 0);
  viterbi.Chainback(decoded.data(), info_bits);
  decoded.resize(static_cast<std::size_t>((info_bits + 7) / 8));
  if (info_bits % 8) decoded.back() &= static_cast<std::uint8_t>(0xFF << (8 - info_bits % 8));
  const auto coded = Convolve(decoded, info_bits, shape.code);
  for (int k = 0; k < coded_bits; ++k) out.corrected += (llr[static_cast<std::size_t>(k)] > 0.0f) != (coded[static_cast<std::size_t>(k)] != 0);
  out.bytes = std::move(decoded);
  return out;
}

Tones Encode(const Payload& payload) {
  const std::vector<int> tones =
      EncodeBlock(std::vector<std::uint8_t>(payload.begin(), payload.end()), room_phy::kPayloadBits, room_phy::kSymbols);
  Tones out{};
  std::copy(tones.begin(), tones.end(), out.begin());
  return out;
}

Decoded Decode(const SoftBits& soft) {
  const DecodedBlock block = DecodeBlock(std::vector<float>(soft.begin(), soft.end()), room_phy::kPayloadBits);
  Decoded out;
  std::copy(block.bytes.begin(), block.bytes.end(), out.payload.begin());
  out.corrected = block.corrected;
  return out;
}

}  // namespace nava_modem::room_code
