#include "nava_modem/fsk_modulator.h"

#include <algorithm>
#include <cmath>

#include "nava_modem/frame.h"

namespace nava_modem {
namespace {

constexpr double kFadeSeconds = 0.002;

}  // namespace

FskModulator::FskModulator(const ModemOptions& options) : options_(options) {
  ValidateModemOptions(options_);
}

std::vector<float> FskModulator::Modulate(const std::vector<std::uint8_t>& bits) const {
  const double per_bit = SamplesPerBit(options_);
  const std::size_t total = static_cast<std::size_t>(std::ceil(bits.size() * per_bit));
  std::vector<float> out(total);
  auto tone = [&](std::size_t k) { return bits[k] ? options_.mark_hz : options_.space_hz; };
  const double ramp = options_.transition;  // bits
  const double fade = std::min(kFadeSeconds * options_.sample_rate, total / 4.0);
  double phase = 0.0;
  for (std::size_t n = 0; n < total; ++n) {
    const double t = n / per_bit;  // in bits
    const std::size_t k = std::min(bits.size() - 1, static_cast<std::size_t>(t));
    double f = tone(k);
    // Near a boundary with a different bit, blend towards it along half a raised cosine; the
    // two halves meet at the boundary at the mid frequency.
    const double into = t - k;  // 0..1 through bit k
    if (ramp > 0.0 && into < ramp / 2.0 && k > 0 && bits[k - 1] != bits[k]) {
      const double w = 0.5 + 0.5 * std::cos(M_PI * (0.5 + into / ramp));  // 0.5 -> 0
      f = w * tone(k - 1) + (1.0 - w) * f;
    } else if (ramp > 0.0 && into > 1.0 - ramp / 2.0 && k + 1 < bits.size() && bits[k + 1] != bits[k]) {
      const double w = 0.5 - 0.5 * std::cos(M_PI * (0.5 - (1.0 - into) / ramp));  // 0 -> 0.5
      f = w * tone(k + 1) + (1.0 - w) * f;
    }
    double gain = options_.amplitude;
    if (n < fade) gain *= 0.5 - 0.5 * std::cos(M_PI * n / fade);
    if (total - 1 - n < fade) gain *= 0.5 - 0.5 * std::cos(M_PI * (total - 1 - n) / fade);
    out[n] = static_cast<float>(gain * std::sin(phase));
    phase += 2.0 * M_PI * f / options_.sample_rate;
    if (phase > 2.0 * M_PI) phase -= 2.0 * M_PI;
  }
  return out;
}

std::vector<float> FskModulator::ModulatePacket(const std::vector<std::uint8_t>& data) const {
  return Modulate(PacketBits(MakeFrame(data, options_.crc)));
}

}  // namespace nava_modem
