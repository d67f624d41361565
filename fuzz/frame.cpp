// The frame parser and its repair: the bytes and soft decisions a demodulator hands them.
//   byte 0: bit 0 the CRC variant (xmodem), bits 1.. the bits the repair may flip (mod 3);
//   bytes 1-7: a frame as the UART read it;
//   then up to 56 floats (little-endian, any value): the soft decisions on its bits; the frame's
//   own bits, as +-1, stand for those missing.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "nava_modem/frame.h"
#include "nava_modem/frame_repair.h"

using namespace nava_modem;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1 + kFrameBytes) return 0;
  const CrcVariant crc = (data[0] & 1) ? CrcVariant::kXmodem : CrcVariant::kCcittFalse;
  const int max_fixed_bits = (data[0] >> 1) % 3;
  Frame frame;
  std::memcpy(frame.data(), data + 1, kFrameBytes);
  data += 1 + kFrameBytes;
  size -= 1 + kFrameBytes;

  // The packet's bits read back by the UART give the frame again, every character framed.
  const std::vector<std::uint8_t> bits = PacketBits(frame);
  if (bits.size() != static_cast<std::size_t>(kPacketBits)) std::abort();
  for (int k = 0; k < kFrameBytes; ++k) {
    const UartByte byte = ReadUartByte(bits.data() + kBreakSpaceBits + kBreakMarkBits + k * kBitsPerByte);
    if (!byte.framed || byte.value != frame[k]) std::abort();
  }
  // A frame made from its own data matches its CRC.
  const std::vector<std::uint8_t> payload(frame.begin() + 1, frame.begin() + 1 + kDataBytes);
  if (!CrcMatches(MakeFrame(payload, crc), crc)) std::abort();
  // Any other length is refused.
  try {
    MakeFrame(std::vector<std::uint8_t>(payload.begin(), payload.begin() + (data[-1] % kDataBytes)), crc);
    std::abort();
  } catch (const std::invalid_argument&) {
  }

  SoftFrame soft;
  for (int b = 0; b < kFrameDataBits; ++b) soft[b] = ((frame[b / 8] >> (b % 8)) & 1) ? 1.0f : -1.0f;
  std::memcpy(soft.data(), data, std::min(size, sizeof(float) * kFrameDataBits));
  const auto repaired = RepairFrame(soft, crc, max_fixed_bits);
  if (repaired) {
    // What a repair returns is a valid frame, at most max_fixed_bits from the hard decisions.
    if (repaired->frame[0] != kHeader || !CrcMatches(repaired->frame, crc)) std::abort();
    if (repaired->fixed_bits < 0 || repaired->fixed_bits > max_fixed_bits) std::abort();
    const Frame hard = HardFrame(soft);
    int differ = 0;
    for (int k = 0; k < kFrameBytes; ++k) differ += __builtin_popcount(hard[k] ^ repaired->frame[k]);
    if (differ != repaired->fixed_bits) std::abort();
  }
  return 0;
}
