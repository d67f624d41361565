#pragma once

// The `room` profile receiver's first look at a packet's data: the tone energies of its symbol
// windows, each window one FFT, laid where a sender whose clock runs `stretch` times
// slower than ours put its symbols (the windows are that much longer and the tones that much
// lower, so each tone still falls on a bin). No ROS.
#include <cstdint>
#include <vector>

#include "nava_modem/sample_ring.h"

namespace nava_modem {

class RoomSymbolReader {
 public:
  explicit RoomSymbolReader(double sample_rate) : sample_rate_(sample_rate) {}

  // The tone energies (squared amplitudes) of tone bins kLowestBin.. of the `count` symbol
  // windows after the chirp that starts at sample `pre` of `heard` (kSymbols for today's packet;
  // a long frame's header or payload), into `energy` (`count` rows of kBins, sized by the
  // caller); with `stride` k only every k-th row from the first (the others are left as they
  // were: HopContrast's cheaper first look needs no more).
  void Read(const SampleRing& heard, double pre, double stretch, int count, std::vector<double>& energy, int stride);
  double sample_rate() const { return sample_rate_; }

 private:
  // The energies of the window of `length` samples from `first` into `energies` (kBins).
  void Window(const SampleRing& heard, std::int64_t first, int length, double* energies);

  double sample_rate_;
};

}  // namespace nava_modem
