#include "nava_modem/clock_search.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "nava_modem/frame.h"

namespace nava_modem {
namespace {

// The break's first MARK bits do not count in the clock fit: they lie under SPACE's reverberant
// tail while MARK's own sound builds up, and in a room they pull the fit a bit or two late (with
// a wrong rate to make up for it); without these two, measured rooms at DRR 0 to +2 dB read
// about a tenth more packets.
constexpr int kMarkSettleBits = 2;

}  // namespace

NormalizedTones::NormalizedTones(const ToneRing& ring, const ToneModel& model, std::int64_t from, std::int64_t to,
                                 std::int64_t heard)
    : start_(from), values_(static_cast<std::size_t>(std::max<std::int64_t>(0, to - from))) {
  for (std::size_t k = 0; k < values_.size(); ++k) {
    const std::int64_t n = start_ + static_cast<std::int64_t>(k);
    if (n >= heard) {
      values_[k] = 0.0f;
      continue;
    }
    values_[k] = static_cast<float>((ring.mark_power(n) - model.floor[0]) / model.level[0] -
                                    (ring.space_power(n) - model.floor[1]) / model.level[1]);
  }
}

double ClockFitMetric(const NormalizedTones& tones, double first_mark, double period) {
  // The clock search calls this some two thousand times a packet: the bits' weights are made
  // once, and the rounding is done inline (std::llround is a library call).
  static const std::array<int, kEndBitFromMark - kFirstBitFromMark> weight = [] {
    std::array<int, kEndBitFromMark - kFirstBitFromMark> w{};
    for (int k = kFirstBitFromMark; k < kEndBitFromMark; ++k) {
      const int known = KnownPacketBit(k + kBreakSpaceBits);
      // 1: counts for MARK; -1: for SPACE; 2: either way (an unknown bit's strength); 0: not at all.
      w[static_cast<std::size_t>(k - kFirstBitFromMark)] = k >= 0 && k < kMarkSettleBits ? 0 : known < 0 ? 2 : known ? 1 : -1;
    }
    return w;
  }();
  double sum = 0.0;
  for (int k = kFirstBitFromMark; k < kEndBitFromMark; ++k) {
    const int w = weight[static_cast<std::size_t>(k - kFirstBitFromMark)];
    if (w == 0) continue;
    const double at = first_mark + (k + 1) * period - 0.5;  // rounded: floor(x - 1 + 0.5)
    std::int64_t n = static_cast<std::int64_t>(at);
    if (static_cast<double>(n) > at) --n;
    const double v = tones(n);
    sum += w == 2 ? std::abs(v) : w * v;
  }
  return sum;
}

ClockFit BestClock(const NormalizedTones& tones, double start0, double period0, double phase_span, double phase_step,
                   double rate_span, double rate_step) {
  ClockFit best{start0, period0, -1e300};
  for (double r = -rate_span; r <= rate_span + 1e-12; r += rate_step) {
    const double period = period0 * (1.0 + r);
    for (double p = -phase_span; p <= phase_span + 1e-9; p += phase_step) {
      const double metric = ClockFitMetric(tones, start0 + p, period);
      if (metric > best.metric) best = {start0 + p, period, metric};
    }
  }
  return best;
}

std::vector<ClockFit> ClockCandidates(const NormalizedTones& tones, double break_step, double per_bit, double phase_span,
                                      double max_rate_error, std::size_t count) {
  const int rates = static_cast<int>(std::lround(max_rate_error / kClockRateStep));
  std::vector<ClockFit> per_rate;
  for (int k = -rates; k <= rates; ++k) {
    per_rate.push_back(BestClock(tones, break_step, per_bit * (1.0 + k * kClockRateStep), phase_span, per_bit / 8.0, 0.0, 1.0));
  }
  std::vector<ClockFit> candidates;
  for (std::size_t k = 0; k < per_rate.size(); ++k) {
    const bool left = k == 0 || per_rate[k].metric >= per_rate[k - 1].metric;
    const bool right = k + 1 == per_rate.size() || per_rate[k].metric >= per_rate[k + 1].metric;
    if (left && right) candidates.push_back(per_rate[k]);
  }
  std::sort(candidates.begin(), candidates.end(), [](const ClockFit& a, const ClockFit& b) { return a.metric > b.metric; });
  if (candidates.size() > count) candidates.resize(count);
  return candidates;
}

}  // namespace nava_modem
