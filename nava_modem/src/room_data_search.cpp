#include "nava_modem/room_data_search.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>

#include "nava_modem/hop_contrast.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {
namespace {

using namespace room_phy;

// The symbols are read at trial distances kDataSearchStepS apart across the clock tolerance.
// A step of 2 ms is at most 1 ms off: a symbol window 2.5 % of its length at the packet's end,
// the highest tone 3 Hz of its 25. Below kScanContrast the best trial is noise (16 equal tones in
// white noise give about 1.4 a trial, the best of a scan's up to about 1.7; packets heard at all
// give 2.5 or more) and nothing is decoded. Speech is tonal: most of its lone chirps pass, and
// each adds up to 2 * kScanDecoded CRC trials.
// The trials are judged first on every kScanStride-th symbol (21 of 42, spread over the packet,
// so a wrong clock still slides off them), and the best kScanFinalists at least kScanApart from
// each other again on all 42: about half the FFTs of judging every trial whole (speech's lone
// chirps, one every few seconds, each cost a scan). The contrast is broad, and where the
// reverberation rings on it has a second hump some 40 ms (a symbol) later, as high as the true
// one (windows late by up to a symbol still hear their own tone ring): the best kScanDecoded
// humps are decoded, best first.
constexpr double kScanApart = 0.010;
constexpr double kScanContrast = 1.8;
constexpr int kScanStride = 2, kScanFinalists = 3, kScanDecoded = 2;

struct Trial {
  double contrast, distance;
  int index;  // of the trial, kDataSearchStepS apart
  bool operator>(const Trial& o) const { return contrast > o.contrast; }
};

}  // namespace

std::vector<double> SearchByData(RoomSymbolReader& symbols, const SampleRing& heard, double pre, double nominal, double shortest,
                                 double longest, std::size_t chirp_length) {
  const double step = kDataSearchStepS * symbols.sample_rate();
  std::vector<double> energy(static_cast<std::size_t>(kSymbols) * kBins);
  const int apart_steps = static_cast<int>(std::lround(kScanApart / kDataSearchStepS));
  std::vector<Trial> trials;  // contrast on every kScanStride-th symbol
  int index = 0;
  for (double d = shortest; d <= longest; d += step, ++index) {
    if (pre + d + static_cast<double>(chirp_length) > static_cast<double>(heard.count())) continue;
    symbols.Read(heard, pre, d / nominal, kSymbols, energy, kScanStride);
    const double contrast = HopContrast(energy, kScanStride);
    // (Audio that is not finite scores NaN, which no ordering can sort.)
    if (std::isfinite(contrast)) trials.push_back({contrast, d, index});
  }
  std::stable_sort(trials.begin(), trials.end(), std::greater<Trial>());
  std::vector<Trial> finalists;  // contrast on all symbols
  for (const Trial& t : trials) {
    if (finalists.size() == static_cast<std::size_t>(kScanFinalists)) break;
    const bool apart = std::none_of(finalists.begin(), finalists.end(), [&](const Trial& f) { return std::abs(f.index - t.index) < apart_steps; });
    if (!apart) continue;
    symbols.Read(heard, pre, t.distance / nominal, kSymbols, energy, 1);
    const double contrast = HopContrast(energy);
    if (std::isfinite(contrast)) finalists.push_back({contrast, t.distance, t.index});
  }
  std::stable_sort(finalists.begin(), finalists.end(), std::greater<Trial>());
  std::vector<double> out;
  for (std::size_t k = 0; k < finalists.size() && k < static_cast<std::size_t>(kScanDecoded); ++k) {
    if (finalists[k].contrast < kScanContrast) break;
    out.push_back(finalists[k].distance);
  }
  return out;
}

}  // namespace nava_modem
