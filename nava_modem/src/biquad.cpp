#include "nava_modem/biquad.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace nava_modem {

double Biquad::Run(double x) {
  double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
  if (std::abs(y) < 1e-30) y = 0.0;  // no denormals decaying through long silences
  x2 = x1;
  x1 = x;
  y2 = y1;
  y1 = y;
  return y;
}

Biquad PassSection(double sample_rate, double hz, bool high_pass, double q) {
  const double w = 2.0 * M_PI * hz / sample_rate;
  const double alpha = std::sin(w) / (2.0 * q);
  const double c = std::cos(w);
  const double a0 = 1.0 + alpha;
  Biquad s;
  s.b0 = (high_pass ? 1.0 + c : 1.0 - c) / 2.0 / a0;
  s.b1 = (high_pass ? -(1.0 + c) : 1.0 - c) / a0;
  s.b2 = s.b0;
  s.a1 = -2.0 * c / a0;
  s.a2 = (1.0 - alpha) / a0;
  return s;
}

Biquad PeakingSection(double sample_rate, double hz, double gain_db, double q) {
  // Beyond Nyquist the section's poles leave the unit circle: refused, not run unstable.
  if (!(hz > 0.0 && hz < sample_rate / 2.0) || !(q > 0.0) || !std::isfinite(gain_db)) {
    throw std::invalid_argument("peaking section at " + std::to_string(hz) + " Hz, q " + std::to_string(q) + ", " +
                                std::to_string(gain_db) + " dB: expected a centre between 0 and half of " +
                                std::to_string(sample_rate) + " Hz, q above 0 and a finite gain");
  }
  const double w = 2.0 * M_PI * hz / sample_rate;
  const double alpha = std::sin(w) / (2.0 * q);
  const double amplitude = std::pow(10.0, gain_db / 40.0);
  const double c = std::cos(w);
  const double a0 = 1.0 + alpha / amplitude;
  Biquad s;
  s.b0 = (1.0 + alpha * amplitude) / a0;
  s.b1 = -2.0 * c / a0;
  s.b2 = (1.0 - alpha * amplitude) / a0;
  s.a1 = -2.0 * c / a0;
  s.a2 = (1.0 - alpha / amplitude) / a0;
  return s;
}

std::vector<Biquad> Butterworth(double sample_rate, double hz, bool high_pass, int order) {
  if (order < 2 || order > 16 || order % 2 != 0) {
    throw std::invalid_argument("Butterworth order " + std::to_string(order) + ": expected an even number 2..16");
  }
  if (!(hz > 0.0 && hz < sample_rate / 2.0)) {
    throw std::invalid_argument("Butterworth corner " + std::to_string(hz) + " Hz: expected between 0 and half of " +
                                std::to_string(sample_rate) + " Hz");
  }
  // The analogue prototype's poles in conjugate pairs, pair k at angle (2k + 1) pi / (2 order)
  // from the imaginary axis: each pair is a section of quality 1 / (2 sin(angle)).
  std::vector<Biquad> sections;
  for (int k = 0; k < order / 2; ++k) {
    const double angle = M_PI * (2.0 * k + 1.0) / (2.0 * order);
    sections.push_back(PassSection(sample_rate, hz, high_pass, 1.0 / (2.0 * std::sin(angle))));
  }
  return sections;
}

std::vector<double> FilterForward(std::vector<double> x, const std::vector<Biquad>& sections) {
  for (Biquad s : sections) {
    for (double& v : x) v = s.Run(v);
  }
  return x;
}

std::vector<double> FilterForwardBackward(std::vector<double> x, const std::vector<Biquad>& sections) {
  for (int pass = 0; pass < 2; ++pass) {
    x = FilterForward(std::move(x), sections);
    std::reverse(x.begin(), x.end());
  }
  return x;
}

}  // namespace nava_modem
