#include "nava_modem/tone_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "nava_modem/frame.h"
#include "nava_modem/math_constants.h"

namespace nava_modem {
namespace {

// The tone model (FitToneModel). Bits of the break whose windows lie inside its SPACE half and
// its MARK half even with the bit rate max_rate_error off and the break found a bit or two off.
constexpr int kSpaceFirst = -17, kSpaceLast = -3, kMarkFirst = 2, kMarkLast = 17;
// The SPACE tail's decay is read from three groups of bits in the MARK half, 6 bits apart.
constexpr int kGroupBits = 6, kGroup1 = 2, kGroupWidth = 4;
// The decay across the groups must exceed this share of the last group's power to count as
// a tail rather than noise's wander (the group means vary by about a third in white noise).
constexpr double kTailSignificance = 1.0;
constexpr double kMaxDecay = 0.985;  // per bit: RT60 about 4 s at 300 bits/s

}  // namespace

ToneModel FitToneModel(const ToneRing& ring, double break_step, double per_bit) {
  // The mean of a tone's filter over the windows of bits first..last of the break (bit 0 its
  // first MARK bit), on the clock of the detector's estimate.
  auto mean = [&](int tone, int first, int last) {
    const std::int64_t lo = std::llround(break_step + (first + 1) * per_bit - 1.0);
    const std::int64_t hi = std::llround(break_step + (last + 1) * per_bit - 1.0);
    double sum = 0.0;
    for (std::int64_t n = lo; n <= hi; ++n) sum += tone == 0 ? ring.mark_power(n) : ring.space_power(n);
    return sum / static_cast<double>(hi - lo + 1);
  };
  ToneModel model;
  // With SPACE off in the MARK half, the SPACE filter shows the room's tail of the 20 SPACE
  // bits decaying (plus the noise floor): three group means, g_i = floor + t0 decay^c_i, give
  // the decay per bit, the tail at the step and the floor.
  const double c1 = kGroup1 + kGroupWidth / 2.0;
  const double g1 = mean(1, kGroup1, kGroup1 + kGroupWidth);
  const double g2 = mean(1, kGroup1 + kGroupBits, kGroup1 + kGroupBits + kGroupWidth);
  const double g3 = mean(1, kGroup1 + 2 * kGroupBits, kGroup1 + 2 * kGroupBits + kGroupWidth);
  double t0 = 0.0;
  if (g1 > g2 && g2 > g3 && g1 - g3 > kTailSignificance * g3) {
    const double decay = std::min(kMaxDecay, std::pow((g2 - g3) / (g1 - g2), 1.0 / kGroupBits));
    model.decay = decay;
    t0 = (g1 - g2) / (std::pow(decay, c1) * (1.0 - std::pow(decay, kGroupBits)));
    model.floor[1] = std::max(0.0, g3 - t0 * std::pow(decay, c1 + 2 * kGroupBits));
  } else {
    model.floor[1] = mean(1, kMarkFirst, kMarkLast);
  }
  const double a = model.decay, a20 = std::pow(a, kBreakSpaceBits);
  // The SPACE tail builds up over the SPACE half towards t0 at the step: subtract its mean
  // there from the SPACE level to leave the direct power.
  double built = 0.0;
  for (int k = kSpaceFirst; k <= kSpaceLast; ++k) built += t0 * (1.0 - std::pow(a, k + kBreakSpaceBits)) / (1.0 - a20 + kTiny);
  built /= kSpaceLast - kSpaceFirst + 1;
  model.floor[0] = mean(0, kSpaceFirst, kSpaceLast);
  const double space_level = mean(1, kSpaceFirst, kSpaceLast) - model.floor[1] - built;
  model.level[1] = std::max(space_level, 0.1 * (space_level + built));
  // Tail power added per bit of a tone, over its direct power: the same for MARK (one room).
  model.gain = t0 > 0.0 ? t0 * (1.0 - a) / (model.level[1] * (1.0 - a20)) : 0.0;
  // MARK's own tail builds up over the MARK half likewise.
  double growth = 0.0;
  for (int k = kMarkFirst; k <= kMarkLast; ++k) growth += model.gain * (1.0 - std::pow(a, k)) / (1.0 - a);
  growth /= kMarkLast - kMarkFirst + 1;
  model.level[0] = std::max(mean(0, kMarkFirst, kMarkLast) - model.floor[0], 0.0) / (1.0 + growth);
  const double weak = kTiny + 1e-6 * std::max(model.level[0], model.level[1]);
  model.level[0] = std::max(model.level[0], weak);
  model.level[1] = std::max(model.level[1], weak);
  model.tail[0] = model.gain * model.level[0] * (1.0 - a20) / (1.0 - a + kTiny);
  model.tail[1] = t0 * a20;
  return model;
}

}  // namespace nava_modem
