#include "nava_modem/noise_spectrum.h"

#include <algorithm>
#include <limits>

namespace nava_modem {

NoiseSpectrum::NoiseSpectrum(std::size_t bins, std::size_t smooth_bins, std::size_t blocks)
    : smooth_(smooth_bins), ring_(std::max<std::size_t>(1, blocks), std::vector<double>(bins, 0.0)),
      noise_(bins, 0.0), cumulative_(bins + 1, 0.0) {}

void NoiseSpectrum::Add(const std::vector<double>& power) {
  const std::size_t bins = noise_.size();
  for (std::size_t k = 0; k < bins; ++k) cumulative_[k + 1] = cumulative_[k] + power[k];
  std::vector<double>& smoothed = ring_[next_];
  for (std::size_t k = 0; k < bins; ++k) {
    const std::size_t lo = k >= smooth_ ? k - smooth_ : 0, hi = std::min(bins - 1, k + smooth_);
    smoothed[k] = (cumulative_[hi + 1] - cumulative_[lo]) / static_cast<double>(hi + 1 - lo);
  }
  next_ = (next_ + 1) % ring_.size();
  filled_ = std::min(filled_ + 1, ring_.size());
  for (std::size_t k = 0; k < bins; ++k) {
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < filled_; ++b) least = std::min(least, ring_[b][k]);
    noise_[k] = least;
  }
}

}  // namespace nava_modem
