#include "nava_modem/real_fft.h"

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include <fftw3.h>

namespace nava_modem {
namespace {

bool HasOnlySmallFactors(std::size_t n) {
  for (std::size_t p : {2, 3, 5, 7}) {
    while (n % p == 0) n /= p;
  }
  return n == 1;
}

}  // namespace

// The scene renderer may render rooms on several threads.
std::mutex& FftwPlannerMutex() {
  static std::mutex m;
  return m;
}

std::size_t FftSize(std::size_t n) {
  if (n <= 1) return 1;
  while (!HasOnlySmallFactors(n)) ++n;
  return n;
}

std::vector<std::complex<double>> ForwardFft(const std::vector<double>& x, std::size_t n) {
  if (n == 0) throw std::invalid_argument("ForwardFft: size 0");
  std::vector<double> in(n, 0.0);
  std::copy(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(std::min(n, x.size())), in.begin());
  std::vector<std::complex<double>> out(n / 2 + 1);
  fftw_plan plan;
  {
    const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    // FFTW_ESTIMATE: each size is used once or twice, so measuring would cost more than it saves.
    plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), in.data(), reinterpret_cast<fftw_complex*>(out.data()),
                                FFTW_ESTIMATE);
  }
  fftw_execute(plan);
  {
    const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    fftw_destroy_plan(plan);
  }
  return out;
}

std::vector<double> InverseFft(const std::vector<std::complex<double>>& spectrum, std::size_t n) {
  if (n == 0 || spectrum.size() != n / 2 + 1) throw std::invalid_argument("InverseFft: spectrum size does not match n");
  std::vector<std::complex<double>> in = spectrum;  // c2r overwrites its input
  std::vector<double> out(n);
  fftw_plan plan;
  {
    const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    plan = fftw_plan_dft_c2r_1d(static_cast<int>(n), reinterpret_cast<fftw_complex*>(in.data()), out.data(),
                                FFTW_ESTIMATE);
  }
  fftw_execute(plan);
  {
    const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    fftw_destroy_plan(plan);
  }
  const double scale = 1.0 / static_cast<double>(n);
  for (double& v : out) v *= scale;
  return out;
}

}  // namespace nava_modem
