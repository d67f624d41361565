#include <algorithm>
#include <cmath>
#include <optional>

#include "nava_modem/bit_likelihood.h"
#include "nava_modem/frame_reading.h"
#include "nava_modem/math_constants.h"

namespace nava_modem {
namespace {

// Bit repairs (FrameRepair) are allowed only on clocks within this of the nominal rate: the
// receiver searches max_rate_error (3.5 %) for robustness, but sound cards are within a few
// tenths of a percent, and the far clocks are where wrong fits to echoes or noise land.
constexpr double kRepairRateLimit = 0.015;
// Bits a repair may flip in a reading decided on the break's model of the tones.
constexpr int kMaxBreakModelRepairs = 1;
// Start and stop bits (of 14) a clock's reading may get wrong and still have its frame repaired.
constexpr int kMaxMisframedRepaired = 2;

// The data bits' log-likelihood ratios with each tone's level and floor read from the frame's
// own bits. The break shows each tone held steady, which a room colours by its steady-state
// response (a fade of several dB at one frequency, another at the other), not as the short bits
// arrive; so each tone's level and floor are read again from the frame: the known bits (start,
// stop, header) and the others as first decided.
SoftFrame FrameModelSoft(const FrameReading& r) {
  double sum[2][2] = {}, sum2[2][2] = {};  // [tone][on]
  int count[2][2] = {};
  for (int j = 0; j < kFrameBits; ++j) {
    const int known = KnownPacketBit(kBreakSpaceBits + kBreakMarkBits + j);
    const int bit = known < 0 ? r.hard[static_cast<std::size_t>(j)] : known;
    for (int t = 0; t < 2; ++t) {
      const int on = (t == 0) == (bit == 1);
      const double heard = r.heard[static_cast<std::size_t>(t)][static_cast<std::size_t>(j)];
      sum[t][on] += heard;
      sum2[t][on] += heard * heard;
      ++count[t][on];
    }
  }
  double level[2], noise[2], var_level = 0.0, var_noise = 0.0;
  for (int t = 0; t < 2; ++t) {
    if (count[t][0] < 2 || count[t][1] < 2) return SoftFrame{};
    const double on = sum[t][1] / count[t][1], off = sum[t][0] / count[t][0];
    noise[t] = std::max(off, kTiny);
    level[t] = std::max(on - off, kMinToneNoise * on + kTiny);
    // The variance of the log of each mean.
    const double var_on = std::max(0.0, sum2[t][1] / count[t][1] - on * on) / count[t][1];
    const double var_off = std::max(0.0, sum2[t][0] / count[t][0] - off * off) / count[t][0];
    var_level += (var_on + var_off) / (level[t] * level[t]);
    var_noise += var_off / (noise[t] * noise[t]);
  }
  ShrinkTones(level, var_level);
  ShrinkTones(noise, var_noise);
  SoftFrame soft{};
  for (int j = 0; j < kFrameBits; ++j) {
    const int pos = j % kBitsPerByte;
    if (pos >= 1 && pos <= 8) {
      soft[static_cast<std::size_t>((j / kBitsPerByte) * 8 + pos - 1)] =
          static_cast<float>(BitLlr(level, noise, r.heard[0][static_cast<std::size_t>(j)], r.heard[1][static_cast<std::size_t>(j)]));
    }
  }
  return soft;
}

}  // namespace

RxEvent AcceptReading(const FrameReading& r, CrcVariant crc, int max_fixed_bits) {
  RxEvent ev;
  ev.start = r.start;
  ev.end = r.end;
  ev.level_db = r.level_db;
  ev.quality = r.quality;
  ev.rate_error = r.rate_error;
  // A clock fitted this far off is rarer in a sound card than a wrong fit to a room's echoes or
  // to noise, whose reading the CRC must then pass unrepaired.
  const int max_fixed = std::abs(ev.rate_error) > kRepairRateLimit ? 0 : max_fixed_bits;
  std::optional<RepairedFrame> repaired = RepairFrame(FrameModelSoft(r), crc, max_fixed);
  // The break's model of the tones is blind to a room's early echoes, and its log-likelihoods
  // can then be sure of three or more wrong bits; a two-bit repair of such a reading once passed
  // the CRC with a wrong packet (FskRobustness.DiscreteEarlyReflectionsAFewBitsLate), so it
  // gets one.
  if (!repaired) repaired = RepairFrame(r.soft, crc, std::min(max_fixed, kMaxBreakModelRepairs));
  // The start and stop bits are checks the CRC does not see: a reading that got more of them
  // wrong than this has more wrong data bits than a repair should trust (a one-bit repair of a
  // reading with three wrong framing bits passed the CRC with a wrong packet in a measured room
  // whose reverberation was scaled to DRR +4 dB).
  const std::uint8_t* hard = r.hard.data();
  if (repaired && repaired->fixed_bits > 0) {
    int misframed = 0;
    for (int c = 0; c < kFrameBytes; ++c) misframed += (hard[c * kBitsPerByte] != 0) + (hard[c * kBitsPerByte + 9] != 1);
    if (misframed > kMaxMisframedRepaired) repaired.reset();
  }
  if (repaired) {
    ev.kind = RxEvent::Kind::kPacket;
    ev.data.assign(repaired->frame.begin() + 1, repaired->frame.begin() + 1 + kDataBytes);
    ev.fixed_bits = repaired->fixed_bits;
    return ev;
  }
  ev.kind = RxEvent::Kind::kNoise;
  bool any_framed = false;
  for (int c = 0; c < kFrameBytes; ++c) any_framed = any_framed || ReadUartByte(hard + c * kBitsPerByte).framed;
  const UartByte header = ReadUartByte(hard);
  if (!any_framed) {
    ev.noise = RxEvent::Noise::kZeroByte;
  } else if (!header.framed || header.value != kHeader) {
    ev.noise = RxEvent::Noise::kOneByte;
  } else {
    ev.noise = RxEvent::Noise::kBadCrc;
  }
  return ev;
}

}  // namespace nava_modem
