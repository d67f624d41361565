#include "nava_modem/hop_contrast.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nava_modem/room_phy.h"

namespace nava_modem {

using namespace room_phy;

double HopContrast(const std::vector<double>& energy, int stride) {
  const std::size_t expected = static_cast<std::size_t>(kSymbols) * kBins;
  if (energy.size() != expected) {
    throw std::invalid_argument("HopContrast: " + std::to_string(energy.size()) + " tone energies, expected " +
                                std::to_string(expected) + " (" + std::to_string(kSymbols) + " symbols of " +
                                std::to_string(kBins) + " tones)");
  }
  if (stride < 1) throw std::invalid_argument("HopContrast: stride " + std::to_string(stride) + ", expected 1 or more");
  double sum = 0.0;
  int counted = 0;
  for (int s = 0; s < kSymbols; s += stride, ++counted) {
    const double* row = &energy[static_cast<std::size_t>(s) * kBins + static_cast<std::size_t>(Bin(s, 0) - kLowestBin)];
    const double* strongest = std::max_element(row, row + kTonesPerBand);
    double rest = 0.0;
    for (int m = 0; m < kTonesPerBand; ++m) rest += row[m];
    rest = (rest - *strongest) / (kTonesPerBand - 1);
    sum += std::log((*strongest + 1e-30) / (rest + 1e-30));
  }
  return sum / counted;
}

}  // namespace nava_modem
