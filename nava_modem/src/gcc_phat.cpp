#include "nava_modem/gcc_phat.h"

#include <cmath>

#include "nava_modem/fft_plan.h"
#include "nava_modem/power_of_two.h"

namespace nava_modem {
namespace {

using Complex = std::complex<double>;

// Cross-power this far under the band's strongest bin is taken for noise and left out of the
// PHAT sum (40 dB): the nava profile puts its energy in two tones and PHAT would give every
// empty bin the weight of a tone.
constexpr double kWeakBin = 1e-4;

}  // namespace

GccPhat::GccPhat(const BandLayout& layout, double sample_rate, double high_hz, double max_delay)
    : low_bin_(layout.low_bin),
      interpolation_(PowerOfTwoAtLeast(8.0 * high_hz / sample_rate)),
      inverse_(layout.segment * interpolation_),
      half_(std::min<std::ptrdiff_t>(
          static_cast<std::ptrdiff_t>(std::ceil((max_delay * sample_rate + 2.0) * static_cast<double>(interpolation_))),
          static_cast<std::ptrdiff_t>(inverse_ / 2 - 1))),
      backward_(std::make_shared<const FftPlan>(FftKind::kComplexToReal, inverse_)) {}

PairCorrelation GccPhat::Correlate(const BandSpectra& s, std::size_t i, std::size_t j) const {
  PairCorrelation r;
  r.cross.assign(s.bins, Complex(0.0, 0.0));
  for (std::size_t g = 0; g < s.segments; ++g) {
    const Complex* xi = s.channel[i].data() + g * s.bins;
    const Complex* xj = s.channel[j].data() + g * s.bins;
    for (std::size_t b = 0; b < s.bins; ++b) r.cross[b] += std::conj(xi[b]) * xj[b];
  }
  std::vector<double> magnitude(s.bins);
  double strongest = 0.0;
  for (std::size_t b = 0; b < s.bins; ++b) {
    r.power += std::sqrt(s.power[i][b] * s.power[j][b]);
    magnitude[b] = std::sqrt(std::norm(r.cross[b]));
    strongest = std::max(strongest, magnitude[b]);
  }

  r.half = half_;
  r.lags.assign(static_cast<std::size_t>(2 * r.half + 1), 0.0);
  if (strongest <= 0.0) return r;

  // Fresh buffers start zeroed: the bins outside the band stay so.
  FftBuffers buffers = backward_->MakeBuffers();
  Complex* bins = buffers.complex_input();
  for (std::size_t b = 0; b < s.bins; ++b) {
    if (magnitude[b] <= kWeakBin * strongest) continue;
    // Same bin index in the longer inverse transform = same frequency: the zero padding
    // interpolates the lags by `interpolation_`.
    bins[low_bin_ + b] = Complex(r.cross[b].real() / magnitude[b], r.cross[b].imag() / magnitude[b]);
    ++r.used;
  }
  backward_->Execute(buffers);
  const double* lags = buffers.real_output();
  // c2r counts each bin with its mirror: a clean delay peaks at 2 x used.
  const double scale = 1.0 / (2.0 * static_cast<double>(r.used));
  const std::ptrdiff_t inverse = static_cast<std::ptrdiff_t>(inverse_);
  for (std::ptrdiff_t m = -r.half; m <= r.half; ++m) {
    const std::size_t at = static_cast<std::size_t>((m + inverse) % inverse);
    r.lags[static_cast<std::size_t>(m + r.half)] = lags[at] * scale;
  }
  return r;
}

}  // namespace nava_modem
