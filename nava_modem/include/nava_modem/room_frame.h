#pragma once

// The `room` profile's frames of any length (1 to 255 data bytes). Today's 4-byte packet stays
// as it was on the air (room_phy.h); every other frame is a long frame:
//
//   [chirp A] [header: 16 symbols] [chirp B] [payload: the data and a CRC-32, at its rate] [chirp C]
//
// - The header says the payload's rate and length: 13 bits (rate 2, length - 1 8, a CRC-3 over
//   both) through the same code as today's packet, which makes it the more robust of the two:
//   the same protection for each of far fewer bits. Its chirps A and B stand 0.76 s apart,
//   where no other frame puts two chirps (today's packet puts them 1.80 s apart), and their
//   distance gives the sender's clock for the header as a packet's chirps do.
// - The payload follows B; its length, known from the header, says where C must start, and the
//   distance from B to C the sender's clock for the payload. Its CRC-32 covers the header's
//   bits and the data, so a header read wrong is never a frame.
// - Both blocks hop over the sub-bands as today's packet does, each from its own first symbol.
#include <cstdint>
#include <optional>
#include <vector>

#include "nava_modem/room_code.h"
#include "nava_modem/room_phy.h"

namespace nava_modem::room_frame {

constexpr int kMinBytes = 1, kMaxBytes = 255;
// The rate ladder's steps, each a shape of the payload's block (room_code::BlockShape): how many
// sub-bands sound at once and the code's rate.
//   0 "robust": today's coding, one tone of 16 a symbol, rate 1/3;
//   1 "medium": three tones a symbol, each sub-band resting 3 symbols between uses, rate 1/2;
//   2 "fast":   six tones a symbol, each sub-band resting 1 symbol, rate 1/2.
// Each tone of a symbol gets an equal share of the amplitude's power.
constexpr int kRates = 3;
// Each step's name, for tools and docs; "?" for a step the ladder lacks.
const char* RateName(int rate);
// The payload's block shape at a step of the ladder (0 <= rate < kRates).
room_code::BlockShape PayloadShape(int rate);
constexpr int kRateFieldValues = 4;  // the header's rate field has room for this many steps
static_assert(kRates <= kRateFieldValues, "the header names every rate");

constexpr int kHeaderBits = 13;
constexpr int kHeaderSymbols = 16;  // (13 + 8) * 3 = 63 coded bits, and one spare
constexpr int kCrcBits = 32;

struct Header {
  int rate = 0;
  int bytes = 0;  // data bytes, kMinBytes..kMaxBytes
  bool operator==(const Header& o) const { return rate == o.rate && bytes == o.bytes; }
};

// Whether a frame of `bytes` at `rate` is today's packet (4 bytes at rate 0), sent as before.
inline bool IsPacket(int bytes, int rate) { return bytes == 4 && rate == 0; }

// The header's 13 bits, most significant first, in 2 bytes.
std::vector<std::uint8_t> HeaderBytes(const Header& header);
// The header those bits say, if their CRC-3 holds and the rate is one of the ladder's.
std::optional<Header> ParseHeader(const std::vector<std::uint8_t>& bits);

// The payload block's bits (data and CRC-32) and the symbols they take at `rate`.
inline int PayloadBits(int bytes) { return 8 * bytes + kCrcBits; }
int PayloadSymbols(int bytes, int rate);

// The CRC-32 (ISO-HDLC, as zlib's) over the header's two bytes and the data.
std::uint32_t FrameCrc(const Header& header, const std::vector<std::uint8_t>& data);
// The payload block's bytes: the data, then the CRC-32, high byte first.
std::vector<std::uint8_t> PayloadBytes(const Header& header, const std::vector<std::uint8_t>& data);
// The data of a decoded payload block, if its CRC-32 matches.
std::optional<std::vector<std::uint8_t>> CheckedData(const Header& header, const std::vector<std::uint8_t>& block);

// Seconds from a chirp's start to the next's: A to B, and B to C for a payload.
constexpr double HeaderPairSeconds() { return room_phy::kChirpSeconds + kHeaderSymbols * room_phy::kSymbolSeconds; }
double PayloadPairSeconds(int bytes, int rate);
// A frame's airtime, today's packet included.
double FrameSeconds(int bytes, int rate);

}  // namespace nava_modem::room_frame
