#pragma once

// The direction estimator's second stage (direction_estimator.h): one microphone pair's
// generalised cross-correlation with the phase transform (GCC-PHAT), over the lags a far-field
// source can give it. No ROS.
#include <algorithm>
#include <complex>
#include <cstddef>
#include <memory>
#include <vector>

#include "nava_modem/band_spectra.h"

namespace nava_modem {

class FftPlan;

struct PairCorrelation {
  std::vector<std::complex<double>> cross;  // Welch-averaged conj(X_i) X_j per band bin
  double power = 0.0;        // sum over band bins of sqrt(S_ii S_jj): what `cross` could be at most
  std::size_t used = 0;      // bins in the PHAT sum (0: nothing in the band)
  std::ptrdiff_t half = 0;   // lags[m] is at lag (m - half) steps
  std::vector<double> lags;  // GCC-PHAT, 1 for a clean delay

  // The correlation at lag `step` (lag steps, fractional), linear between steps, clamped to the
  // lags kept.
  double At(double step) const {
    const double x = std::clamp(step + static_cast<double>(half), 0.0, static_cast<double>(lags.size() - 1));
    const std::size_t k = std::min(static_cast<std::size_t>(x), lags.size() - 2);
    const double f = x - static_cast<double>(k);
    return lags[k] * (1.0 - f) + lags[k + 1] * f;
  }
};

// PHAT: every band bin of the cross-spectrum is normalised to unit magnitude, so the peak is as
// sharp as the band allows whatever the source's spectrum, and a room's colouring does not widen
// it; bins more than 40 dB below the band's strongest cross-power are dropped (with the nava
// profile's two tones most of the band is noise, which PHAT would otherwise weigh as much as the
// tones). The inverse FFT is zero-padded so that a lag step is at most 1/(8 high_hz). Copies
// share the FFT plan; Correlate() is const and may run on several threads at once.
class GccPhat {
 public:
  // `layout`: the analysis the spectra come from; lags are kept within +-`max_delay` (s) plus 2
  // samples.
  GccPhat(const BandLayout& layout, double sample_rate, double high_hz, double max_delay);

  // The correlation of channels i and j of `spectra` (> 0 lags: the sound reaches j later).
  PairCorrelation Correlate(const BandSpectra& spectra, std::size_t i, std::size_t j) const;
  std::size_t interpolation() const { return interpolation_; }  // lag steps per sample

 private:
  std::size_t low_bin_, interpolation_, inverse_;
  std::ptrdiff_t half_;
  std::shared_ptr<const FftPlan> backward_;
};

}  // namespace nava_modem
