#include "nava_modem/first_arrival.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>

#include "nava_modem/fft_plan.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/power_of_two.h"

namespace nava_modem {
namespace {

// The band's edges are rolled off over this much inside it (a raised cosine), so that the
// envelope's ringing before a pulse stays far below the kDirectWithinDb threshold; a brick wall
// rings at -13 dB.
constexpr double kRollOffHz = 300.0;
// Where the reference is weaker than this share of its strongest in-band power, the division
// is held back (a Wiener-like regularisation): its noise would swamp the response there.
constexpr double kRegularisation = 1e-3;
// (The envelope is read on the sample grid: a 4.8 kHz band sampled at 11 kHz or more is smooth
// between samples, and the half-peak crossing interpolated linearly moves with a fractional
// delay to within a microsecond, as first_arrival_test checks.)
// A measured response is judged around its largest sample, this far either side: the direct
// sound and the early reflections, and enough margin that the band-pass has no edge effects.
constexpr double kResponseWindowS = 0.05;

double BandWeight(double f) {
  if (f <= kResponseBandLowHz || f >= kResponseBandHighHz) return 0.0;
  const double from_edge = std::min(f - kResponseBandLowHz, kResponseBandHighHz - f);
  if (from_edge >= kRollOffHz) return 1.0;
  return 0.5 - 0.5 * std::cos(M_PI * from_edge / kRollOffHz);
}

// The first peak of `env` within kDirectWithinDb of its largest, then the point (in units of
// env's samples, interpolated) where the envelope rising to it first reaches half of it. NaN
// for an envelope that is zero everywhere.
double HalfPeakEdge(const std::vector<double>& env) {
  const double largest = env.empty() ? 0.0 : *std::max_element(env.begin(), env.end());
  if (!(largest > 0.0) || !std::isfinite(largest)) return std::numeric_limits<double>::quiet_NaN();
  const double threshold = largest * std::pow(10.0, -kDirectWithinDb / 20.0);
  std::size_t p = 0;
  while (env[p] < threshold) ++p;
  while (p + 1 < env.size() && env[p + 1] >= env[p]) ++p;
  const double half = 0.5 * env[p];
  std::size_t j = p;
  while (j > 0 && env[j - 1] >= half) --j;
  if (j == 0) return 0.0;  // already above half where the search begins
  return static_cast<double>(j - 1) + (half - env[j - 1]) / (env[j] - env[j - 1]);
}

}  // namespace

double FirstArrival(const float* received, std::size_t count, const std::vector<float>& reference, double sample_rate,
                    double* clarity) {
  if (clarity) *clarity = 0.0;
  if (reference.empty()) throw std::invalid_argument("first arrival: expected a reference sound, got none");
  if (count < reference.size()) {
    throw std::invalid_argument("first arrival: " + std::to_string(count) + " samples received, expected at least the reference's " +
                                std::to_string(reference.size()));
  }
  if (!(sample_rate >= 2.0 * kResponseBandHighHz) || !std::isfinite(sample_rate)) {
    throw std::invalid_argument("first arrival: sample rate " + std::to_string(sample_rate) + " Hz: expected at least " +
                                std::to_string(2.0 * kResponseBandHighHz));
  }
  // Linear, not circular, correlation at delays 0..count - reference.size().
  const std::size_t n = PowerOfTwoAtLeast(static_cast<double>(count + reference.size()));
  FftPlan rx(FftKind::kRealToComplex, n), ref(FftKind::kRealToComplex, n);
  std::fill(rx.real_input(), rx.real_input() + n, 0.0);
  std::fill(ref.real_input(), ref.real_input() + n, 0.0);
  std::copy(received, received + count, rx.real_input());
  std::copy(reference.begin(), reference.end(), ref.real_input());
  rx.Execute();
  ref.Execute();

  const std::size_t bins = n / 2 + 1;
  const double bin_hz = sample_rate / static_cast<double>(n);
  double strongest = 0.0;
  for (std::size_t k = 0; k < bins; ++k) {
    if (BandWeight(static_cast<double>(k) * bin_hz) > 0.0) strongest = std::max(strongest, std::norm(ref.complex_output()[k]));
  }
  if (!(strongest > 0.0)) return std::numeric_limits<double>::quiet_NaN();  // no reference in the band
  const double floor = kRegularisation * strongest;
  // The analytic response: positive frequencies only.
  FftPlan analytic(FftKind::kComplexBackward, n);
  std::complex<double>* z = analytic.complex_input();
  std::fill(z, z + n, std::complex<double>(0.0, 0.0));
  for (std::size_t k = 0; k < bins; ++k) {
    const double w = BandWeight(static_cast<double>(k) * bin_hz);
    if (w == 0.0) continue;
    const std::complex<double> c = ref.complex_output()[k];
    z[k] = w * rx.complex_output()[k] * std::conj(c) / (std::norm(c) + floor);
  }
  analytic.Execute();
  const std::size_t lags = count - reference.size() + 1;
  std::vector<double> env(lags);
  for (std::size_t i = 0; i < lags; ++i) env[i] = std::abs(analytic.complex_output()[i]);
  if (clarity && !env.empty()) {
    std::vector<double> sorted = env;
    const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
    std::nth_element(sorted.begin(), mid, sorted.end());
    const double largest = *std::max_element(env.begin(), env.end());
    *clarity = *mid > 0.0 ? largest / *mid : (largest > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  }
  return HalfPeakEdge(env) / sample_rate;
}

double LeadingEdge(const std::vector<float>& response, double sample_rate) {
  if (response.empty()) throw std::invalid_argument("leading edge: expected a response, got none");
  std::size_t peak = 0;
  for (std::size_t k = 0; k < response.size(); ++k) {
    if (std::abs(response[k]) > std::abs(response[peak])) peak = k;
  }
  const std::size_t half = static_cast<std::size_t>(std::lround(kResponseWindowS * sample_rate));
  const std::size_t from = peak > half ? peak - half : 0;
  const std::size_t to = std::min(response.size(), peak + half + 1);
  return static_cast<double>(from) / sample_rate + FirstArrival(response.data() + from, to - from, {1.0f}, sample_rate);
}

}  // namespace nava_modem
