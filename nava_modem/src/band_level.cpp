#include "nava_modem/band_level.h"

#include <cmath>

namespace nava_modem {

// Coefficients from the bilinear transform of the analogue 2nd-order Butterworth section
// (Q = 1/sqrt 2), as in R. Bristow-Johnson's audio EQ cookbook.
BandLevel::Biquad BandLevel::Butterworth(double sample_rate, double hz, bool high_pass) {
  const double w = 2.0 * M_PI * hz / sample_rate;
  const double alpha = std::sin(w) / std::sqrt(2.0);
  const double c = std::cos(w);
  const double a0 = 1.0 + alpha;
  Biquad q{};
  if (high_pass) {
    q.b0 = (1.0 + c) / 2.0 / a0;
    q.b1 = -(1.0 + c) / a0;
  } else {
    q.b0 = (1.0 - c) / 2.0 / a0;
    q.b1 = (1.0 - c) / a0;
  }
  q.b2 = q.b0;
  q.a1 = -2.0 * c / a0;
  q.a2 = (1.0 - alpha) / a0;
  return q;
}

double BandLevel::Biquad::Run(double x) {
  double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
  if (std::abs(y) < 1e-30) y = 0.0;  // no denormals decaying through long silences
  x2 = x1;
  x1 = x;
  y2 = y1;
  y1 = y;
  return y;
}

BandLevel::BandLevel(double sample_rate, double low_hz, double high_hz, double seconds)
    : high_pass_(Butterworth(sample_rate, low_hz, true)),
      low_pass_(Butterworth(sample_rate, std::min(high_hz, 0.45 * sample_rate), false)),
      smoothing_(1.0 - std::exp(-1.0 / (seconds * sample_rate))) {}

void BandLevel::Push(float sample) {
  const double y = low_pass_.Run(high_pass_.Run(sample));
  power_ += smoothing_ * (y * y - power_);
  if (power_ < 1e-30) power_ = 0.0;
}

double BandLevel::db() const { return 10.0 * std::log10(power() + 1e-20); }

}  // namespace nava_modem
