#include "nava_modem/room_phy.h"

#include <algorithm>
#include <cmath>

namespace nava_modem::room_phy {
namespace {

// The sub-band order: neighbours in time are 3 to 6 sub-bands (1.2 to 2.4 kHz) apart, and every
// sub-band is used once in 12 symbols.
constexpr std::array<int, kBands> kHops = {0, 6, 3, 9, 1, 7, 4, 10, 2, 8, 5, 11};
constexpr double kChirpTaperSeconds = 0.005;

}  // namespace

int Band(int symbol) { return kHops[static_cast<std::size_t>(symbol % kBands)]; }

int BandOf(int symbol, int slot, int tones) { return Band(symbol * tones + slot); }

std::vector<float> Chirp(double sample_rate) {
  const std::size_t n = static_cast<std::size_t>(std::lround(kChirpSeconds * sample_rate));
  const double rate = (kChirpHighHz - kChirpLowHz) / kChirpSeconds;  // Hz per s
  const double taper = kChirpTaperSeconds * sample_rate;
  std::vector<float> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = k / sample_rate;
    double gain = 1.0;
    const double edge = std::min<double>(k, n - 1 - k);
    if (edge < taper) gain = 0.5 - 0.5 * std::cos(M_PI * edge / taper);
    out[k] = static_cast<float>(gain * std::sin(2.0 * M_PI * (kChirpLowHz * t + 0.5 * rate * t * t)));
  }
  return out;
}

}  // namespace nava_modem::room_phy
