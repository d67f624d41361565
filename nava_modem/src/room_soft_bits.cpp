#include "nava_modem/room_soft_bits.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nava_modem/room_phy.h"

namespace nava_modem {
namespace {

using namespace room_phy;

double Median(std::vector<double>& v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// How much a tone's energy, as a multiple of its noise floor, speaks for it. Logarithmic, so
// that one burst of speech or a click in a wrong tone cannot outvote the other symbols.
double Evidence(double ratio) { return std::log1p(ratio); }

}  // namespace

room_code::SoftBits RoomSoftBits(const std::vector<double>& energy) {
  const std::size_t expected = static_cast<std::size_t>(kSymbols) * kBins;
  if (energy.size() != expected) {
    throw std::invalid_argument("RoomSoftBits: " + std::to_string(energy.size()) + " tone energies, expected " +
                                std::to_string(expected));
  }
  auto at = [&](int s, int b) { return energy[static_cast<std::size_t>(s) * kBins + b]; };
  auto active = [](int s, int b) { return b / kTonesPerBand == Band(s); };

  // Each tone's floor: its median over the symbols that did not use its sub-band.
  std::vector<double> floor(kBins), values;
  for (int b = 0; b < kBins; ++b) {
    values.clear();
    for (int s = 0; s < kSymbols; ++s) {
      if (!active(s, b)) values.push_back(at(s, b));
    }
    floor[b] = Median(values) + 1e-15;
  }
  room_code::SoftBits soft{};
  for (int s = 0; s < kSymbols; ++s) {
    // How loud this symbol's time was across the other sub-bands (speech comes and goes).
    values.clear();
    for (int b = 0; b < kBins; ++b) {
      if (!active(s, b)) values.push_back(at(s, b) / floor[b]);
    }
    const double loudness = std::max(1.0, Median(values));
    std::array<double, kTonesPerBand> e{};
    for (int m = 0; m < kTonesPerBand; ++m) {
      const int b = Bin(s, m) - kLowestBin;
      e[m] = Evidence(at(s, b) / (floor[b] * loudness));
    }
    for (int j = 0; j < kBitsPerSymbol; ++j) {
      const int mask = 1 << (kBitsPerSymbol - 1 - j);
      double one = 0.0, zero = 0.0;
      for (int m = 0; m < kTonesPerBand; ++m) {
        double& side = (room_code::ToneBits(m) & mask) ? one : zero;
        side = std::max(side, e[m]);
      }
      soft[static_cast<std::size_t>(s * kBitsPerSymbol + j)] = static_cast<float>(one - zero);
    }
  }
  return soft;
}

}  // namespace nava_modem
