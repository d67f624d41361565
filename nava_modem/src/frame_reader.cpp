#include <cmath>
#include <cstdint>

#include "nava_modem/bit_clock.h"
#include "nava_modem/bit_likelihood.h"
#include "nava_modem/frame_reading.h"
#include "nava_modem/math_constants.h"

namespace nava_modem {
namespace {

// The bit clock's loop gains: small, because the fit over the whole packet already has the
// clock right to a few hundredths of a bit; the loop only follows what a straight line cannot
// (a resampler's wander).
constexpr double kPhaseGain = 0.1;
constexpr double kPeriodGain = 0.002;
// Crossings are trusted for the loop only between bits decided at least this clearly.
constexpr double kLoopMinSoft = 0.3;

}  // namespace

FrameReading ReadFrame(const FrameSource& source, double best_start, double best_period) {
  const ToneRing& ring = source.ring;
  const ToneModel& model = source.model;
  BitClock clock(best_start, best_period, source.window, kPhaseGain, kPeriodGain);
  FrameReading r;
  double power = 0.0, quality = 0.0;
  int previous = 1;  // the break's last bit is MARK
  double previous_soft = 1.0;
  double tail[2] = {model.tail[0], model.tail[1]};
  // Where each bit of the packet was read, for the equaliser.
  for (int k = kFirstBitFromMark; k < kFrameStartFromMark; ++k) {
    r.at[static_cast<std::size_t>(k - kFirstBitFromMark)] = std::llround(best_start + (k + 1) * best_period - 1.0);
  }
  for (int k = kFrameStartFromMark; k < kEndBitFromMark; ++k) {
    const std::int64_t at = std::llround(clock.AlignedSample(k));
    r.at[static_cast<std::size_t>(k - kFirstBitFromMark)] = at;
    const double e = ring.sum(at);
    // Each tone's filter holds its direct sound, if sent, and a random tail (the room's
    // reverberation of earlier bits, and noise) of known mean power: the log-likelihood that
    // the tone is on (Rician against Rayleigh), MARK's less SPACE's.
    const double noise[2] = {model.floor[0] + tail[0], model.floor[1] + tail[1]};
    const int j = k - kFrameStartFromMark, pos = j % kBitsPerByte;
    const std::size_t bit = static_cast<std::size_t>(j);
    r.heard[0][bit] = ring.mark_power(at);
    r.heard[1][bit] = ring.space_power(at);
    const double llr = BitLlr(model.level, noise, ring.mark_power(at), ring.space_power(at));
    const double v = std::tanh(llr / 2.0);  // P(MARK) - P(SPACE)
    // The tails the next bit sees: what is left of these, and what this bit adds.
    const double mark = (1.0 + v) / 2.0;
    tail[0] = model.decay * tail[0] + model.gain * model.level[0] * mark;
    tail[1] = model.decay * tail[1] + model.gain * model.level[1] * (1.0 - mark);
    r.hard[bit] = llr > 0.0;
    if (pos >= 1 && pos <= 8) r.soft[static_cast<std::size_t>((j / kBitsPerByte) * 8 + pos - 1)] = static_cast<float>(llr);
    power += e;
    quality += ring.amplitude_sum(at);
    // Follow the transition into this bit, if it is clear on both sides.
    if (r.hard[bit] != previous && std::abs(v) > kLoopMinSoft && std::abs(previous_soft) > kLoopMinSoft) {
      const double expected = clock.ExpectedCrossing(k);
      const std::int64_t lo = std::llround(expected - clock.period() / 4.0);
      const std::int64_t hi = std::llround(expected + clock.period() / 4.0);
      double crossing = 0.0, nearest = 1e300;
      for (std::int64_t i = lo + 1; i <= hi; ++i) {
        const double a = source.tones(i - 1), b = source.tones(i);
        if ((a > 0.0) == (b > 0.0) || a == b) continue;
        const double at_zero = (i - 1) + a / (a - b);
        if (std::abs(at_zero - expected) < nearest) {
          nearest = std::abs(at_zero - expected);
          crossing = at_zero;
        }
      }
      if (nearest < 1e300) clock.Observe(k, crossing);
    }
    previous = r.hard[bit];
    previous_soft = v;
  }
  r.start = (best_start - kBreakSpaceBits * best_period) * source.seconds_per_step;
  r.end = clock.Start(kEndBitFromMark) * source.seconds_per_step;
  r.level_db = 10.0 * std::log10(power / kFrameBits + kTiny);
  r.quality = quality / kFrameBits;
  r.rate_error = source.per_bit / best_period - 1.0;
  return r;
}

}  // namespace nava_modem
