#include "nava_modem/frame.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "nava_modem/crc16.h"
#include "nava_modem/frame_repair.h"

namespace nava_modem {
namespace {

TEST(Crc16, CheckValues) {
  const std::string check = "123456789";
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(check.data());
  EXPECT_EQ(Crc16(CrcVariant::kCcittFalse, bytes, check.size()), 0x29B1);
  EXPECT_EQ(Crc16(CrcVariant::kXmodem, bytes, check.size()), 0x31C3);
  EXPECT_EQ(Crc16(CrcVariant::kCcittFalse, {0x55, 0x01, 0x02, 0x03, 0x04}), 0x2A6A);
}

TEST(Crc16, VariantNames) {
  EXPECT_EQ(ParseCrcVariant("ccitt-false"), CrcVariant::kCcittFalse);
  EXPECT_EQ(ParseCrcVariant("xmodem"), CrcVariant::kXmodem);
  EXPECT_FALSE(ParseCrcVariant("crc32").has_value());
  EXPECT_STREQ(CrcVariantName(CrcVariant::kXmodem), "xmodem");
}

TEST(Frame, HeaderDataAndCrcHighByteFirst) {
  const Frame f = MakeFrame({1, 2, 3, 4}, CrcVariant::kCcittFalse);
  EXPECT_EQ(f, (Frame{0x55, 1, 2, 3, 4, 0x2A, 0x6A}));
  EXPECT_TRUE(CrcMatches(f, CrcVariant::kCcittFalse));
  EXPECT_FALSE(CrcMatches(f, CrcVariant::kXmodem));
  EXPECT_THROW(MakeFrame({1, 2, 3}, CrcVariant::kCcittFalse), std::invalid_argument);
  EXPECT_THROW(MakeFrame({1, 2, 3, 4, 5}, CrcVariant::kCcittFalse), std::invalid_argument);
}

TEST(Frame, BitsOnTheAir) {
  const std::vector<std::uint8_t> bits = PacketBits(MakeFrame({0xFF, 0, 0x0F, 0x80}, CrcVariant::kCcittFalse));
  ASSERT_EQ(bits.size(), 110u);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(bits[k], 0) << k;
  for (int k = 20; k < 40; ++k) EXPECT_EQ(bits[k], 1) << k;
  // The header 0x55 in 8N1, LSB first: start 0, 1 0 1 0 1 0 1 0, stop 1.
  const std::vector<std::uint8_t> header(bits.begin() + 40, bits.begin() + 50);
  EXPECT_EQ(header, (std::vector<std::uint8_t>{0, 1, 0, 1, 0, 1, 0, 1, 0, 1}));
  // 0x0F: the low nibble first.
  const std::vector<std::uint8_t> third(bits.begin() + 70, bits.begin() + 80);
  EXPECT_EQ(third, (std::vector<std::uint8_t>{0, 1, 1, 1, 1, 0, 0, 0, 0, 1}));
  const UartByte read = ReadUartByte(bits.data() + 70);
  EXPECT_TRUE(read.framed);
  EXPECT_EQ(read.value, 0x0F);
  std::vector<std::uint8_t> broken(third);
  broken[9] = 0;  // no stop bit
  EXPECT_FALSE(ReadUartByte(broken.data()).framed);
}

SoftFrame Soft(const Frame& f, float sure) {
  SoftFrame s{};
  for (int b = 0; b < kFrameDataBits; ++b) s[b] = (f[b / 8] >> (b % 8)) & 1 ? sure : -sure;
  return s;
}

TEST(FrameRepair, FlipsTheLeastSureBitsOnly) {
  const Frame f = MakeFrame({9, 8, 7, 6}, CrcVariant::kCcittFalse);
  SoftFrame s = Soft(f, 0.9f);
  ASSERT_TRUE(RepairFrame(s, CrcVariant::kCcittFalse, 2).has_value());
  EXPECT_EQ(RepairFrame(s, CrcVariant::kCcittFalse, 2)->fixed_bits, 0);
  // Two unsure bits decided wrong: repaired with 2, not with 1.
  s[12] = -s[12] * 0.1f;
  s[40] = -s[40] * 0.05f;
  EXPECT_FALSE(RepairFrame(s, CrcVariant::kCcittFalse, 1).has_value());
  const auto two = RepairFrame(s, CrcVariant::kCcittFalse, 2);
  ASSERT_TRUE(two.has_value());
  EXPECT_EQ(two->frame, f);
  EXPECT_EQ(two->fixed_bits, 2);
  // A sure bit decided wrong is not guessed at.
  SoftFrame sure = Soft(f, 0.9f);
  sure[3] = -sure[3];
  for (int b = 20; b < 40; ++b) sure[b] *= 0.5f;  // other bits less sure than the wrong one
  EXPECT_FALSE(RepairFrame(sure, CrcVariant::kCcittFalse, 2).has_value());
  EXPECT_FALSE(RepairFrame(s, CrcVariant::kCcittFalse, 0).has_value());
}

TEST(FrameRepair, AnErrorEventOfThreeBitsIsFlippedWhole) {
  const Frame f = MakeFrame({9, 8, 7, 6}, CrcVariant::kCcittFalse);
  SoftFrame s = Soft(f, 0.9f);
  for (int b : {41, 42, 43}) s[b] = -s[b];  // a transition moved: three bits wrong together
  EXPECT_FALSE(RepairFrame(s, CrcVariant::kCcittFalse, 2).has_value());
  // The event, behind weaker ones of two and three bits that do not make the CRC right.
  const std::vector<std::vector<int>> events = {{1, 2}, {20, 21, 22}, {41, 42, 43}, {30, 31, 32}};
  const auto repaired = RepairEvent(s, events, CrcVariant::kCcittFalse, 3, 4);
  ASSERT_TRUE(repaired.has_value());
  EXPECT_EQ(repaired->frame, f);
  EXPECT_EQ(repaired->fixed_bits, 3);
  // Only the weakest `max_events` of 2 to `max_event_bits` bits are tried; single bits are not
  // events here (RepairFrame's).
  EXPECT_FALSE(RepairEvent(s, events, CrcVariant::kCcittFalse, 2, 4).has_value());
  EXPECT_TRUE(RepairEvent(s, {{7}, {1, 2}, {41, 42, 43}}, CrcVariant::kCcittFalse, 2, 4).has_value());
  EXPECT_FALSE(RepairEvent(s, {{41, 42, 43}}, CrcVariant::kCcittFalse, 2, 2).has_value());
  EXPECT_FALSE(RepairEvent(s, {}, CrcVariant::kCcittFalse, 2, 4).has_value());
  EXPECT_THROW(RepairEvent(s, {{41, 42, 56}}, CrcVariant::kCcittFalse, 2, 4), std::invalid_argument);
  EXPECT_THROW(RepairEvent(s, {{-1, 42, 43}}, CrcVariant::kCcittFalse, 2, 4), std::invalid_argument);
  EXPECT_THROW(RepairEvent(s, {{41, 42, 42}}, CrcVariant::kCcittFalse, 2, 4), std::invalid_argument);
}

TEST(FrameRepair, ATransitionMovedByOneBitIsRepairedAsAnEventNotAsAnyPair) {
  const Frame f = MakeFrame({0x3C, 0xA5, 0x0F, 0x81}, CrcVariant::kCcittFalse);
  SoftFrame s = Soft(f, 0.9f);
  // Two neighbouring bits wrong together, decided as surely as the rest (the sequence search
  // found no cheaper competitor for either alone), with six other bits weaker than both.
  for (int b : {17, 18}) s[b] = -s[b];
  for (int b : {3, 9, 25, 33, 47, 52}) s[b] *= 0.3f;
  EXPECT_FALSE(RepairFrame(s, CrcVariant::kCcittFalse, 2).has_value());
  const auto repaired = RepairEvent(s, {{17, 18}}, CrcVariant::kCcittFalse, 1, 4);
  ASSERT_TRUE(repaired.has_value());
  EXPECT_EQ(repaired->frame, f);
  EXPECT_EQ(repaired->fixed_bits, 2);
}

TEST(FrameRepair, OnlyTheEightLeastSureBitsAndPairsOfTheFiveLeastSureAreTried) {
  const Frame f = MakeFrame({1, 2, 3, 4}, CrcVariant::kCcittFalse);
  // One wrong bit, the ninth least sure: eight others are weaker, so it is not tried.
  SoftFrame s = Soft(f, 0.9f);
  s[30] = -0.5f * s[30];
  for (int b = 0; b < 8; ++b) s[b] *= 0.4f;
  EXPECT_FALSE(RepairFrame(s, CrcVariant::kCcittFalse, 1).has_value());
  s[7] /= 0.4f;  // as sure as the rest again: the wrong bit is now the eighth least sure
  ASSERT_TRUE(RepairFrame(s, CrcVariant::kCcittFalse, 1).has_value());
  EXPECT_EQ(RepairFrame(s, CrcVariant::kCcittFalse, 1)->frame, f);
  // Two wrong bits, the weakest and the sixth weakest: no pair of the five least sure makes it.
  SoftFrame two = Soft(f, 0.9f);
  two[12] = -0.05f * two[12];
  two[44] = -0.3f * two[44];
  for (int b : {20, 21, 22, 23}) two[b] *= 0.2f;
  EXPECT_FALSE(RepairFrame(two, CrcVariant::kCcittFalse, 2).has_value());
  two[23] = Soft(f, 0.9f)[23];  // the wrong bit is now the fifth weakest
  ASSERT_TRUE(RepairFrame(two, CrcVariant::kCcittFalse, 2).has_value());
  EXPECT_EQ(RepairFrame(two, CrcVariant::kCcittFalse, 2)->frame, f);
}

}  // namespace
}  // namespace nava_modem
