#include "nava_modem/break_detector.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "nava_modem/math_constants.h"

namespace nava_modem {
namespace {

// Per-sample in-band power below which the detector sees silence (-70 dB of full scale): the
// ratios it takes are meaningless on digital silence.
constexpr double kSilence = 1e-7;

}  // namespace

BreakDetector::BreakDetector(std::int64_t window) : window_(window) {
  if (window <= 0) throw std::invalid_argument("break detector: window of " + std::to_string(window) + " steps: expected at least 1");
}

void BreakDetector::Update(const ToneRing& ring, std::int64_t n) {
  const std::int64_t w = window_;
  after_ += ring.difference(n) - ring.difference(n - w);
  before_ += ring.difference(n - w) - ring.difference(n - 2 * w);
  after_power_ += ring.sum(n) - ring.sum(n - w);
  before_power_ += ring.sum(n - w) - ring.sum(n - 2 * w);
  if ((n & 0xFFFF) == 0) {  // renew the running sums against rounding
    after_ = before_ = after_power_ = before_power_ = 0.0;
    for (std::int64_t k = n - 2 * w + 1; k <= n; ++k) {
      (k > n - w ? after_ : before_) += ring.difference(k);
      (k > n - w ? after_power_ : before_power_) += ring.sum(k);
    }
  }
}

double BreakDetector::Step() const {
  const double floor = kSilence * static_cast<double>(window_);
  const double mixed = std::min(after_ / std::max(after_power_, floor), -before_ / std::max(before_power_, floor));
  // Each tone on its own scale (its larger window's power): balanced, the step peaks where the
  // sums' one would with the tones equal: at the break.
  const double mark_after = (after_power_ + after_) / 2.0, mark_before = (before_power_ + before_) / 2.0;
  const double space_after = (after_power_ - after_) / 2.0, space_before = (before_power_ - before_) / 2.0;
  const double mark_scale = std::max({mark_after, mark_before, floor}), space_scale = std::max({space_after, space_before, floor});
  const double ma = mark_after / mark_scale, mb = mark_before / mark_scale;
  const double sa = space_after / space_scale, sb = space_before / space_scale;
  const double balanced = std::min((ma - sa) / std::max(ma + sa, kTiny), (sb - mb) / std::max(sb + mb, kTiny));
  return std::max(mixed, balanced);
}

}  // namespace nava_modem
