#include "nava_modem/tone_classes.h"

#include <algorithm>
#include <cmath>

namespace nava_modem {
namespace {

// Powers below this share of the frame's largest are taken as this (digital silence has no log).
constexpr double kFloorShare = 1e-9;
// The least spread of a log power the discriminant assumes (natural log, about 1.7 dB): a tone
// that two bits happen to show alike must not become infinitely sure.
constexpr double kMinSpread = 0.2;
// Each tone's say in one bit is bounded, so that one filter's outlier (a deep fade, a click)
// cannot outvote the other.
constexpr double kMaxToneLlr = 12.0;
// Fitted on the known bits, then refitted on all bits as decided this many times.
constexpr int kRefits = 3;

}  // namespace

int KnownFrameBit(int j) {
  const int pos = j % kBitsPerByte, byte = j / kBitsPerByte;
  if (pos == 0) return 0;
  if (pos == 9) return 1;
  if (byte == 0) return (kHeader >> (pos - 1)) & 1;
  return -1;
}

ToneClassDecision ToneClassSoft(const double heard[2][kFrameBits], const std::uint8_t* hard) {
  double largest = 0.0;
  for (int t = 0; t < 2; ++t)
    for (int j = 0; j < kFrameBits; ++j) largest = std::max(largest, heard[t][j]);
  ToneClassDecision out;
  if (!(largest > 0.0)) {
    out.misframed = 2 * kFrameBytes;
    return out;
  }
  double x[2][kFrameBits];
  for (int t = 0; t < 2; ++t)
    for (int j = 0; j < kFrameBits; ++j) x[t][j] = std::log(std::max(heard[t][j], kFloorShare * largest));

  std::uint8_t bit[kFrameBits];
  for (int j = 0; j < kFrameBits; ++j) bit[j] = static_cast<std::uint8_t>(KnownFrameBit(j) >= 0 ? KnownFrameBit(j) : hard[j] != 0);
  double llr[kFrameBits] = {};
  for (int fit = 0; fit <= kRefits; ++fit) {
    // Each tone's mean log power with each kind of bit, and their pooled spread.
    double weight[2], middle[2];
    for (int t = 0; t < 2; ++t) {
      double sum[2] = {0.0, 0.0}, sum2[2] = {0.0, 0.0};
      int count[2] = {0, 0};
      for (int j = 0; j < kFrameBits; ++j) {
        if (fit == 0 && KnownFrameBit(j) < 0) continue;
        sum[bit[j]] += x[t][j];
        sum2[bit[j]] += x[t][j] * x[t][j];
        ++count[bit[j]];
      }
      if (count[0] < 2 || count[1] < 2) {
        out.misframed = 2 * kFrameBytes;
        return out;
      }
      const double mean0 = sum[0] / count[0], mean1 = sum[1] / count[1];
      const double scatter = sum2[0] - count[0] * mean0 * mean0 + sum2[1] - count[1] * mean1 * mean1;
      const double var = std::max(scatter / (count[0] + count[1] - 2), kMinSpread * kMinSpread);
      weight[t] = (mean1 - mean0) / var;
      middle[t] = (mean0 + mean1) / 2.0;
    }
    for (int j = 0; j < kFrameBits; ++j) {
      double l = 0.0;
      for (int t = 0; t < 2; ++t) l += std::clamp(weight[t] * (x[t][j] - middle[t]), -kMaxToneLlr, kMaxToneLlr);
      llr[j] = l;
      if (KnownFrameBit(j) < 0) bit[j] = l > 0.0;
    }
  }
  for (int j = 0; j < kFrameBits; ++j) {
    const int pos = j % kBitsPerByte, known = KnownFrameBit(j);
    if (pos >= 1 && pos <= 8) out.soft[(j / kBitsPerByte) * 8 + pos - 1] = static_cast<float>(llr[j]);
    if ((pos == 0 || pos == 9) && (llr[j] > 0.0) != (known == 1)) ++out.misframed;
  }
  return out;
}

}  // namespace nava_modem
