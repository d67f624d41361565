#pragma once

// The nava receiver's clock search (after the break detector and the tone model): the bit clock
// that best explains a packet's known bits and the strength of its unknown ones, on the tone
// filters' outputs each normalised by the tone model. No ROS.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nava_modem/tone_model.h"
#include "nava_modem/tone_ring.h"

namespace nava_modem {

// The tone filters' difference over a stretch of steps, each tone less its floor and over its
// level (MARK's less SPACE's), so that a tone weaker than the other weighs as much; 0 outside the
// stretch and where not heard yet (no evidence either way).
class NormalizedTones {
 public:
  NormalizedTones() = default;
  // Steps `from` to `to` (not included) of `ring` on `model`; steps from `heard` on read 0.
  NormalizedTones(const ToneRing& ring, const ToneModel& model, std::int64_t from, std::int64_t to, std::int64_t heard);
  double operator()(std::int64_t n) const {
    const std::int64_t k = n - start_;
    return k < 0 || k >= static_cast<std::int64_t>(values_.size()) ? 0.0 : values_[static_cast<std::size_t>(k)];
  }

 private:
  std::int64_t start_ = 0;
  std::vector<float> values_;
};

// A bit clock: the filter step of the break's first MARK bit, steps a bit, and how well it fits
// (ClockFitMetric; -1e300 for none).
struct ClockFit {
  double start, period, metric;
};

// Rates a step apart in the coarse search (ClockCandidates), as a share of the nominal.
constexpr double kClockRateStep = 0.0025;

// How well the clock (first_mark, period) explains the packet: each known bit's normalised
// difference in its sign, each unknown bit's in its size, summed over the packet (the break's
// first MARK bits left out: they lie under SPACE's tail while MARK's own sound builds up).
double ClockFitMetric(const NormalizedTones& tones, double first_mark, double period);

// The best of a grid of clocks around (start0, period0): phases start0 +-phase_span in steps of
// phase_step, periods period0 x (1 +- rate_span) in steps of rate_step.
ClockFit BestClock(const NormalizedTones& tones, double start0, double period0, double phase_span, double phase_step,
                   double rate_span, double rate_step);

// The clocks worth reading the packet on: at each rate kClockRateStep apart within
// +-max_rate_error of `per_bit`, the best phase within +-phase_span of break_step (eighth-bit
// steps); of those, the rates whose fit is a local optimum across rates, best first, at most
// `count` (in deep noise the best fit can be a wrong one).
std::vector<ClockFit> ClockCandidates(const NormalizedTones& tones, double break_step, double per_bit, double phase_span,
                                      double max_rate_error, std::size_t count);

}  // namespace nava_modem
