#pragma once

// The nava receiver's memory of its two tone filters (ToneFilters): per filter step, each tone's
// power and complex amplitude, for the last size() steps. Before the first step the air was
// silent: what lies before step 0 reads as 0. No ROS.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace nava_modem {

class ToneRing {
 public:
  // `size`: a power of two (std::invalid_argument otherwise), the steps kept.
  explicit ToneRing(std::size_t size);
  // Step n's outputs (n one past the last put: steps come in order; older ones are overwritten).
  void Put(std::int64_t n, double mark_power, double space_power, std::complex<double> mark, std::complex<double> space);
  // Each tone's power (as kept: in single precision) and complex amplitude at step n.
  double mark_power(std::int64_t n) const { return n < 0 ? 0.0 : mark_power_[Index(n)]; }
  double space_power(std::int64_t n) const { return n < 0 ? 0.0 : space_power_[Index(n)]; }
  std::complex<double> mark(std::int64_t n) const { return n < 0 ? 0.0 : std::complex<double>(mark_[Index(n)]); }
  std::complex<double> space(std::int64_t n) const { return n < 0 ? 0.0 : std::complex<double>(space_[Index(n)]); }
  // MARK's power less SPACE's, and the two summed.
  double difference(std::int64_t n) const { return mark_power(n) - space_power(n); }
  double sum(std::int64_t n) const { return mark_power(n) + space_power(n); }
  // The two filters' amplitudes summed (the thesis's quality figure), from the difference and
  // the sum of their powers.
  double amplitude_sum(std::int64_t n) const {
    const double d = difference(n), e = sum(n);
    return std::sqrt(std::max(0.0, (e + d) / 2.0)) + std::sqrt(std::max(0.0, (e - d) / 2.0));
  }
  std::size_t size() const { return mark_power_.size(); }

 private:
  std::size_t Index(std::int64_t n) const { return static_cast<std::size_t>(n) & mask_; }
  std::vector<float> mark_power_, space_power_;
  std::vector<std::complex<float>> mark_, space_;
  std::size_t mask_;
};

}  // namespace nava_modem
