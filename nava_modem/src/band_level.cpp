#include "nava_modem/band_level.h"

#include <algorithm>
#include <cmath>

namespace nava_modem {

BandLevel::BandLevel(double sample_rate, double low_hz, double high_hz, double seconds)
    : high_pass_(PassSection(sample_rate, low_hz, true, M_SQRT1_2)),
      low_pass_(PassSection(sample_rate, std::min(high_hz, 0.45 * sample_rate), false, M_SQRT1_2)),
      smoothing_(1.0 - std::exp(-1.0 / (seconds * sample_rate))) {}

void BandLevel::Push(float sample) {
  const double y = low_pass_.Run(high_pass_.Run(sample));
  power_ += smoothing_ * (y * y - power_);
  if (power_ < 1e-30) power_ = 0.0;
}

double BandLevel::db() const { return 10.0 * std::log10(power() + 1e-20); }

}  // namespace nava_modem
