#pragma once

// Whole-signal real FFTs, for the room channel's filters (one big transform per signal: the
// room's impulse response, the tilt and the noise colour are all applied as products of
// spectra, so no block bookkeeping is needed). Each call plans its own FftPlan (fft_plan.h);
// code that transforms blocks of one size again and again keeps an FftPlan instead.
#include <complex>
#include <cstddef>
#include <vector>

namespace nava_modem {

// The smallest size >= n whose only prime factors are 2, 3, 5 and 7 (FFTW is fast on those).
std::size_t FftSize(std::size_t n);

// The n/2 + 1 bins of the DFT of `x` zero-padded (or cut) to n samples. Unnormalised.
std::vector<std::complex<double>> ForwardFft(const std::vector<double>& x, std::size_t n);

// The n real samples whose DFT is `spectrum` (n/2 + 1 bins), scaled by 1/n so that
// InverseFft(ForwardFft(x, n), n) == x.
std::vector<double> InverseFft(const std::vector<std::complex<double>>& spectrum, std::size_t n);

// Frequency of bin k of an n-point DFT at `sample_rate`.
inline double BinHz(std::size_t k, std::size_t n, double sample_rate) {
  return static_cast<double>(k) * sample_rate / static_cast<double>(n);
}

}  // namespace nava_modem
