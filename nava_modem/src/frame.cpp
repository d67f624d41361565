#include "nava_modem/frame.h"

#include <stdexcept>
#include <string>

namespace nava_modem {

Frame MakeFrame(const std::vector<std::uint8_t>& data, CrcVariant crc) {
  if (data.size() != static_cast<std::size_t>(kDataBytes)) {
    throw std::invalid_argument("a Nava packet carries " + std::to_string(kDataBytes) + " data bytes, got " +
                                std::to_string(data.size()));
  }
  Frame f{};
  f[0] = kHeader;
  for (int k = 0; k < kDataBytes; ++k) f[1 + k] = data[k];
  const std::uint16_t c = Crc16(crc, f.data(), 1 + kDataBytes);
  f[kFrameBytes - 2] = static_cast<std::uint8_t>(c >> 8);
  f[kFrameBytes - 1] = static_cast<std::uint8_t>(c & 0xFF);
  return f;
}

std::vector<std::uint8_t> PacketBits(const Frame& frame) {
  std::vector<std::uint8_t> bits;
  bits.reserve(kPacketBits);
  bits.insert(bits.end(), kBreakSpaceBits, 0);
  bits.insert(bits.end(), kBreakMarkBits, 1);
  for (std::uint8_t byte : frame) {
    bits.push_back(0);
    for (int b = 0; b < 8; ++b) bits.push_back((byte >> b) & 1);
    bits.push_back(1);
  }
  return bits;
}

bool CrcMatches(const Frame& frame, CrcVariant crc) {
  const std::uint16_t c = Crc16(crc, frame.data(), 1 + kDataBytes);
  return frame[kFrameBytes - 2] == (c >> 8) && frame[kFrameBytes - 1] == (c & 0xFF);
}

UartByte ReadUartByte(const std::uint8_t* bits) {
  UartByte out;
  for (int b = 0; b < 8; ++b) out.value |= static_cast<std::uint8_t>((bits[1 + b] & 1) << b);
  out.framed = bits[0] == 0 && bits[9] == 1;
  return out;
}

int KnownPacketBit(int k) {
  if (k < kBreakSpaceBits) return 0;
  if (k < kBreakSpaceBits + kBreakMarkBits) return 1;
  const int j = k - kBreakSpaceBits - kBreakMarkBits, pos = j % kBitsPerByte, byte = j / kBitsPerByte;
  if (pos == 0) return 0;  // start bit
  if (pos == 9) return 1;  // stop bit
  if (byte == 0) return (kHeader >> (pos - 1)) & 1;
  return -1;
}

}  // namespace nava_modem
