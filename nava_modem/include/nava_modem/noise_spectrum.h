#pragma once

#include <cstddef>
#include <vector>

namespace nava_modem {

// The noise's power spectrum while signals come and go, by minimum statistics: each block's
// power spectrum, smoothed over `smooth_bins` either side, and the least of the last `blocks`
// of them at each frequency. Packets sound for seconds with gaps between them, so the least is
// the noise's (whine, rumble, hiss), not theirs.
class NoiseSpectrum {
 public:
  NoiseSpectrum(std::size_t bins, std::size_t smooth_bins, std::size_t blocks);

  // The noise estimated from the blocks added so far (zeros before the first).
  const std::vector<double>& noise() const { return noise_; }
  // Adds a block's power per bin (`bins` values).
  void Add(const std::vector<double>& power);

 private:
  std::size_t smooth_;
  std::vector<std::vector<double>> ring_;
  std::size_t next_ = 0, filled_ = 0;
  std::vector<double> noise_, cumulative_;
};

}  // namespace nava_modem
