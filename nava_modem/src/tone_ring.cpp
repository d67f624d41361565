#include "nava_modem/tone_ring.h"

#include <stdexcept>
#include <string>

namespace nava_modem {

ToneRing::ToneRing(std::size_t size)
    : mark_power_(size, 0.0f), space_power_(size, 0.0f), mark_(size), space_(size), mask_(size - 1) {
  if (size == 0 || (size & (size - 1)) != 0) {
    throw std::invalid_argument("tone ring: " + std::to_string(size) + " steps: expected a power of two");
  }
}

void ToneRing::Put(std::int64_t n, double mark_power, double space_power, std::complex<double> mark, std::complex<double> space) {
  const std::size_t k = Index(n);
  mark_power_[k] = static_cast<float>(mark_power);
  space_power_[k] = static_cast<float>(space_power);
  mark_[k] = std::complex<float>(static_cast<float>(mark.real()), static_cast<float>(mark.imag()));
  space_[k] = std::complex<float>(static_cast<float>(space.real()), static_cast<float>(space.imag()));
}

}  // namespace nava_modem
