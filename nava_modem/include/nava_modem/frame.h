#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "nava_modem/crc16.h"

namespace nava_modem {

// The Nava packet on the air (thesis section 5.2.4): a break of 20 bit times of 0 (SPACE) then
// 20 of 1 (MARK), then 7 bytes in 8N1 (start bit 0, 8 data bits LSB first, stop bit 1): the
// header 0x55, 4 data bytes, and the CRC over header and data, high byte first. 110 bit times.
constexpr std::uint8_t kHeader = 0x55;
constexpr int kDataBytes = 4;
constexpr int kFrameBytes = 1 + kDataBytes + 2;
constexpr int kBreakSpaceBits = 20;
constexpr int kBreakMarkBits = 20;
constexpr int kBitsPerByte = 10;  // 8N1
constexpr int kFrameBits = kFrameBytes * kBitsPerByte;                   // 70
constexpr int kPacketBits = kBreakSpaceBits + kBreakMarkBits + kFrameBits;  // 110

// The nava receiver counts a packet's bits from the break's first MARK bit (where its bit clock
// is anchored): the packet's first bit, the frame's first and one past the packet's last.
constexpr int kFirstBitFromMark = -kBreakSpaceBits;
constexpr int kFrameStartFromMark = kBreakMarkBits;
constexpr int kEndBitFromMark = kBreakMarkBits + kFrameBits;

using Frame = std::array<std::uint8_t, kFrameBytes>;

// Header, data and CRC. `data` must hold kDataBytes bytes (std::invalid_argument otherwise).
Frame MakeFrame(const std::vector<std::uint8_t>& data, CrcVariant crc);

// The value bit k of a packet has whatever its data (0 at the break's first SPACE bit; before it,
// SPACE too): 0 or 1 for the break, the start and stop bits and the header; -1 where the data
// and CRC decide.
int KnownPacketBit(int k);

// Every bit of the packet in air order, break included: kPacketBits values of 0 or 1.
std::vector<std::uint8_t> PacketBits(const Frame& frame);

// Whether a frame's CRC matches its header and data.
bool CrcMatches(const Frame& frame, CrcVariant crc);

// One 8N1 character read by the UART from 10 bit decisions.
struct UartByte {
  std::uint8_t value = 0;
  bool framed = false;  // start bit 0 and stop bit 1
};
// `bits` points at a character's 10 bits (start, 8 data LSB first, stop), each 0 or 1.
UartByte ReadUartByte(const std::uint8_t* bits);

}  // namespace nava_modem
