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

// Which sub-bands each of a block's symbols sounds ([symbol][band]).
std::vector<std::vector<bool>> SoundingBands(int symbols, int tones) {
  std::vector<std::vector<bool>> sounding(static_cast<std::size_t>(symbols), std::vector<bool>(kBands, false));
  for (int s = 0; s < symbols; ++s) {
    for (int j = 0; j < tones; ++j) sounding[static_cast<std::size_t>(s)][static_cast<std::size_t>(BandOf(s, j, tones))] = true;
  }
  return sounding;
}

// Sounding several sub-bands at once, each rests only a few symbols between uses, and the tone it
// sounded last still rings when it sounds again. The symbol just before, where the sub-band
// rested, hears that ring alone: what it heard, decayed by one more symbol, is taken off. The
// decay is read from the block itself: the median, over the sub-bands' uses followed by a rest,
// of the loudest tone's energy in the rest over its energy in the use (an underestimate where the
// direct sound was strong, so the ring is never taken off more than it was).
std::vector<double> WithoutTails(const std::vector<double>& energy, int symbols, int tones) {
  auto at = [&](int s, int b) { return energy[static_cast<std::size_t>(s) * kBins + static_cast<std::size_t>(b)]; };
  const std::vector<std::vector<bool>> sounding = SoundingBands(symbols, tones);
  std::vector<double> ratios;
  for (int s = 0; s + 1 < symbols; ++s) {
    for (int band = 0; band < kBands; ++band) {
      if (!sounding[static_cast<std::size_t>(s)][static_cast<std::size_t>(band)] ||
          sounding[static_cast<std::size_t>(s + 1)][static_cast<std::size_t>(band)]) {
        continue;
      }
      int loudest = band * kTonesPerBand;
      for (int m = 1; m < kTonesPerBand; ++m) {
        if (at(s, band * kTonesPerBand + m) > at(s, loudest)) loudest = band * kTonesPerBand + m;
      }
      if (at(s, loudest) > 0.0) ratios.push_back(at(s + 1, loudest) / at(s, loudest));
    }
  }
  const double decay = std::min(1.0, Median(ratios));
  std::vector<double> out = energy;
  for (int s = 1; s < symbols; ++s) {
    for (int b = 0; b < kBins; ++b) {
      const int band = b / kTonesPerBand;
      if (!sounding[static_cast<std::size_t>(s)][static_cast<std::size_t>(band)] ||
          sounding[static_cast<std::size_t>(s - 1)][static_cast<std::size_t>(band)]) {
        continue;
      }
      double& e = out[static_cast<std::size_t>(s) * kBins + static_cast<std::size_t>(b)];
      e = std::max(0.1 * e, e - decay * at(s - 1, b));
    }
  }
  return out;
}

}  // namespace

std::vector<float> RoomSoftBits(const std::vector<double>& energy, int symbols, int tones) {
  const std::size_t expected = static_cast<std::size_t>(std::max(symbols, 0)) * kBins;
  if (symbols < 1 || energy.size() != expected) {
    throw std::invalid_argument("RoomSoftBits: " + std::to_string(energy.size()) + " tone energies for " +
                                std::to_string(symbols) + " symbols, expected " + std::to_string(expected));
  }
  if (tones < 1 || tones > kBands / 2) {
    // (Each tone's floor is read where its sub-band rests: at least half the symbols.)
    throw std::invalid_argument("RoomSoftBits: " + std::to_string(tones) + " tones a symbol, expected 1 to " +
                                std::to_string(kBands / 2));
  }
  const std::vector<double> heard = tones > 1 ? WithoutTails(energy, symbols, tones) : std::vector<double>{};
  const std::vector<double>& use = tones > 1 ? heard : energy;
  auto at = [&](int s, int b) { return use[static_cast<std::size_t>(s) * kBins + b]; };
  // Which sub-bands each symbol sounds.
  const std::vector<std::vector<bool>> sounding = SoundingBands(symbols, tones);
  auto active = [&](int s, int b) { return sounding[static_cast<std::size_t>(s)][static_cast<std::size_t>(b / kTonesPerBand)]; };

  // Each tone's floor: its median over the symbols that did not use its sub-band.
  std::vector<double> floor(kBins), values;
  for (int b = 0; b < kBins; ++b) {
    values.clear();
    for (int s = 0; s < symbols; ++s) {
      if (!active(s, b)) values.push_back(at(s, b));
    }
    floor[b] = Median(values) + 1e-15;
  }
  std::vector<float> soft(static_cast<std::size_t>(symbols * tones) * kBitsPerSymbol);
  for (int s = 0; s < symbols; ++s) {
    // How loud this symbol's time was across the other sub-bands (speech comes and goes).
    values.clear();
    for (int b = 0; b < kBins; ++b) {
      if (!active(s, b)) values.push_back(at(s, b) / floor[b]);
    }
    const double loudness = std::max(1.0, Median(values));
    for (int slot = 0; slot < tones; ++slot) {
      std::array<double, kTonesPerBand> e{};
      const int first = BandOf(s, slot, tones) * kTonesPerBand;
      for (int m = 0; m < kTonesPerBand; ++m) e[m] = Evidence(at(s, first + m) / (floor[first + m] * loudness));
      for (int j = 0; j < kBitsPerSymbol; ++j) {
        const int mask = 1 << (kBitsPerSymbol - 1 - j);
        double one = 0.0, zero = 0.0;
        for (int m = 0; m < kTonesPerBand; ++m) {
          double& side = (room_code::ToneBits(m) & mask) ? one : zero;
          side = std::max(side, e[m]);
        }
        soft[static_cast<std::size_t>((s * tones + slot) * kBitsPerSymbol + j)] = static_cast<float>(one - zero);
      }
    }
  }
  return soft;
}

room_code::SoftBits RoomSoftBits(const std::vector<double>& energy) {
  const std::vector<float> soft = RoomSoftBits(energy, kSymbols);
  room_code::SoftBits out{};
  std::copy(soft.begin(), soft.end(), out.begin());
  return out;
}

}  // namespace nava_modem
