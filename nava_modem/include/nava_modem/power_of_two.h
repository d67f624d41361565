#pragma once

#include <cstddef>

namespace nava_modem {

// The smallest power of two >= n: the size of a ring indexed by masking, or of a radix-2 FFT.
inline std::size_t PowerOfTwoAtLeast(double n) {
  std::size_t size = 1;
  while (static_cast<double>(size) < n) size <<= 1;
  return size;
}

}  // namespace nava_modem
