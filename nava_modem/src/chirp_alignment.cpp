#include "nava_modem/chirp_alignment.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace nava_modem {
namespace {

// A chirp's missing partner counts when its peak is this many times the mean output over
// kSearchBackground seconds ending kSearchGuard seconds before the window searched.
constexpr double kSearchRatio = 4.0;
constexpr double kSearchBackground = 0.3, kSearchGuard = 0.02;

}  // namespace

std::int64_t AlignmentLookahead(double sample_rate) { return std::llround((kAlignAfterS + kAlignReachS) * sample_rate) + 1; }

ChirpShape ShapeOf(const ChirpDetector& detector, double sample_rate, const ChirpPeak& anchor) {
  const std::int64_t before = std::llround(kAlignBeforeS * sample_rate), after = std::llround(kAlignAfterS * sample_rate);
  const std::int64_t p = std::llround(anchor.sample);
  ChirpShape shape{anchor.sample, std::vector<double>(static_cast<std::size_t>(before + after))};
  for (std::int64_t i = -before; i < after; ++i) shape.envelope[static_cast<std::size_t>(i + before)] = std::sqrt(detector.Envelope(p + i));
  return shape;
}

std::vector<double> LineUpChirp(const ChirpDetector& detector, double sample_rate, const ChirpPeak& anchor, double around,
                                double reach_s, int picks) {
  return LineUpShape(detector, sample_rate, ShapeOf(detector, sample_rate, anchor), around, reach_s, picks);
}

std::vector<double> LineUpShape(const ChirpDetector& detector, double sample_rate, const ChirpShape& shape, double around,
                                double reach_s, int picks) {
  const double fs = sample_rate;
  const std::int64_t before = std::llround(kAlignBeforeS * fs), after = std::llround(kAlignAfterS * fs);
  const std::int64_t reach = std::max<std::int64_t>(1, std::llround(reach_s * fs));
  const std::int64_t p = std::llround(shape.sample), q = std::llround(around);
  const std::vector<double>& a = shape.envelope;
  std::vector<double> b(static_cast<std::size_t>(before + after + 2 * reach));
  for (std::int64_t i = -before - reach; i < after + reach; ++i) b[static_cast<std::size_t>(i + before + reach)] = std::sqrt(detector.Envelope(q + i));
  std::vector<double> score(static_cast<std::size_t>(2 * reach + 1));
  // Eight lags at a time: each lag's sum runs over i in the same order as one lag alone would (the
  // same value to the bit), but the eight chains are independent, so they overlap and vectorise
  // where one chain would wait on each addition (this was the receiver's costliest loop).
  constexpr std::size_t kLags = 8;
  std::size_t lag = 0;
  for (; lag + kLags <= score.size(); lag += kLags) {
    double sum[kLags] = {};
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double x = a[i];
      const double* y = &b[i + lag];
      for (std::size_t k = 0; k < kLags; ++k) sum[k] += x * y[k];
    }
    for (std::size_t k = 0; k < kLags; ++k) score[lag + k] = sum[k];
  }
  for (; lag < score.size(); ++lag) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i + lag];
    score[lag] = sum;
  }
  // The best lag and the best one at least a millisecond from it (a reflection in one chirp
  // lined up with the direct sound in the other scores nearly as well), each to a fraction of
  // a sample.
  const std::int64_t apart = std::llround(0.001 * fs);
  std::vector<double> out;
  std::size_t first = score.size();
  for (int pick = 0; pick < picks; ++pick) {
    std::size_t best = score.size();
    for (std::size_t lag = 1; lag + 1 < score.size(); ++lag) {
      const bool local = score[lag] >= score[lag - 1] && score[lag] >= score[lag + 1];
      const bool far = first == score.size() || std::llabs(static_cast<std::int64_t>(lag) - static_cast<std::int64_t>(first)) >= apart;
      if (local && far && (best == score.size() || score[lag] > score[best])) best = lag;
    }
    if (best == score.size()) break;
    if (pick == 0) first = best;
    double refined = static_cast<double>(best);
    const double l = score[best - 1], c = score[best], r = score[best + 1];
    const double denom = l - 2.0 * c + r;
    // (Not ParabolaOffset: a NaN curvature, from audio that is not finite, leaves the lag whole.)
    if (denom < 0.0) refined += std::clamp(0.5 * (l - r) / denom, -0.5, 0.5);
    // The anchor's fractional part carries over: the lag is between whole samples.
    out.push_back(shape.sample + static_cast<double>(q - p) + refined - static_cast<double>(reach));
  }
  return out;
}

std::vector<double> AlignedPosts(const ChirpDetector& detector, double sample_rate, const ChirpPeak& pre, const ChirpPeak& post) {
  std::vector<double> out = LineUpChirp(detector, sample_rate, pre, post.sample, kAlignReachS, 2);
  out.push_back(post.sample);
  return out;
}

std::optional<ChirpPeak> StrongestChirpIn(const ChirpDetector& detector, double sample_rate, double from, double to) {
  const std::int64_t first = std::max<std::int64_t>(0, std::llround(from)), last = std::llround(to);
  if (last <= first || last >= detector.computed()) return std::nullopt;
  ChirpPeak best;
  for (std::int64_t n = first; n <= last; ++n) {
    const double p = detector.Envelope(n);
    if (p > best.power) best = {static_cast<double>(n), 0.0, p};
  }
  // Against the filter's mean output before the window, as the detector judges.
  const std::int64_t guard = std::llround(kSearchGuard * sample_rate);
  const std::int64_t span = std::llround(kSearchBackground * sample_rate);
  double sum = 0.0;
  for (std::int64_t n = first - guard - span; n < first - guard; ++n) sum += detector.Envelope(n);
  best.ratio = best.power / std::max(sum / static_cast<double>(span), 1e-20);
  if (best.ratio < kSearchRatio) return std::nullopt;
  return best;
}

}  // namespace nava_modem
