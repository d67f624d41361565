#include "nava_modem/real_fft.h"

#include <algorithm>
#include <stdexcept>

#include "nava_modem/fft_plan.h"

namespace nava_modem {
namespace {

bool HasOnlySmallFactors(std::size_t n) {
  for (std::size_t p : {2, 3, 5, 7}) {
    while (n % p == 0) n /= p;
  }
  return n == 1;
}

}  // namespace

std::size_t FftSize(std::size_t n) {
  if (n <= 1) return 1;
  while (!HasOnlySmallFactors(n)) ++n;
  return n;
}

std::vector<std::complex<double>> ForwardFft(const std::vector<double>& x, std::size_t n) {
  if (n == 0) throw std::invalid_argument("ForwardFft: size 0");
  FftPlan plan(FftKind::kRealToComplex, n);
  // The plan's input starts zeroed: copying the first n samples zero-pads a short x.
  std::copy(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(std::min(n, x.size())), plan.real_input());
  plan.Execute();
  return std::vector<std::complex<double>>(plan.complex_output(), plan.complex_output() + plan.output_length());
}

std::vector<double> InverseFft(const std::vector<std::complex<double>>& spectrum, std::size_t n) {
  if (n == 0 || spectrum.size() != n / 2 + 1) throw std::invalid_argument("InverseFft: spectrum size does not match n");
  FftPlan plan(FftKind::kComplexToReal, n);
  std::copy(spectrum.begin(), spectrum.end(), plan.complex_input());
  plan.Execute();
  std::vector<double> out(plan.real_output(), plan.real_output() + n);
  const double scale = 1.0 / static_cast<double>(n);
  for (double& v : out) v *= scale;
  return out;
}

}  // namespace nava_modem
