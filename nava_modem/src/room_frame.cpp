#include "nava_modem/room_frame.h"

#include <boost/crc.hpp>

namespace nava_modem::room_frame {
namespace {

// CRC-3 (x^3 + x + 1) over the header's 10 field bits.
unsigned HeaderCheck(unsigned fields) {
  boost::crc_basic<3> crc(0x3, 0x0, 0x0, false, false);
  crc.process_bits(static_cast<unsigned char>(fields >> 8), 2);
  crc.process_bits(static_cast<unsigned char>(fields & 0xFF), 8);
  return crc.checksum();
}

}  // namespace

namespace {

struct Step {
  const char* name;
  room_code::BlockShape shape;
};
constexpr Step kSteps[kRates] = {
    {"robust", {1, room_code::Code::kThirdK9}},
    {"medium", {3, room_code::Code::kHalfK9}},
    {"fast", {6, room_code::Code::kHalfK9}},
};

}  // namespace

const char* RateName(int rate) { return rate >= 0 && rate < kRates ? kSteps[rate].name : "?"; }

room_code::BlockShape PayloadShape(int rate) { return kSteps[rate].shape; }

std::vector<std::uint8_t> HeaderBytes(const Header& header) {
  const unsigned fields = (static_cast<unsigned>(header.rate) << 8) | static_cast<unsigned>(header.bytes - 1);
  const unsigned bits = (fields << 3) | HeaderCheck(fields);  // 13 bits
  return {static_cast<std::uint8_t>(bits >> 5), static_cast<std::uint8_t>((bits & 0x1F) << 3)};
}

std::optional<Header> ParseHeader(const std::vector<std::uint8_t>& bits) {
  if (bits.size() < 2) return std::nullopt;
  const unsigned value = (static_cast<unsigned>(bits[0]) << 5) | (bits[1] >> 3);
  const unsigned fields = value >> 3;
  if ((value & 0x7u) != HeaderCheck(fields)) return std::nullopt;
  const Header header{static_cast<int>(fields >> 8), static_cast<int>(fields & 0xFF) + 1};
  if (header.rate >= kRates) return std::nullopt;
  return header;
}

int PayloadSymbols(int bytes, int rate) { return room_code::BlockSymbols(PayloadBits(bytes), PayloadShape(rate)); }

std::uint32_t FrameCrc(const Header& header, const std::vector<std::uint8_t>& data) {
  boost::crc_32_type crc;
  const std::vector<std::uint8_t> head = HeaderBytes(header);
  crc.process_bytes(head.data(), head.size());
  crc.process_bytes(data.data(), data.size());
  return crc.checksum();
}

std::vector<std::uint8_t> PayloadBytes(const Header& header, const std::vector<std::uint8_t>& data) {
  std::vector<std::uint8_t> out(data);
  const std::uint32_t crc = FrameCrc(header, data);
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(crc >> shift));
  return out;
}

std::optional<std::vector<std::uint8_t>> CheckedData(const Header& header, const std::vector<std::uint8_t>& block) {
  if (block.size() != static_cast<std::size_t>(header.bytes) + 4) return std::nullopt;
  std::vector<std::uint8_t> data(block.begin(), block.begin() + header.bytes);
  std::uint32_t sent = 0;
  for (std::size_t k = data.size(); k < block.size(); ++k) sent = (sent << 8) | block[k];
  if (sent != FrameCrc(header, data)) return std::nullopt;
  return data;
}

double PayloadPairSeconds(int bytes, int rate) {
  return room_phy::kChirpSeconds + PayloadSymbols(bytes, rate) * room_phy::kSymbolSeconds;
}

double FrameSeconds(int bytes, int rate) {
  if (IsPacket(bytes, rate)) return room_phy::kPacketSeconds;
  return HeaderPairSeconds() + PayloadPairSeconds(bytes, rate) + room_phy::kChirpSeconds;
}

}  // namespace nava_modem::room_frame
