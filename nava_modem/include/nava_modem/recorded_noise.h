#pragma once

// A noise as a modem's receiver hears it: its power and how that power spreads over frequency,
// read from a recording (a fan, a corridor, a kitchen), so that a recorded noise can be weighed
// against the white noise a decode table was measured with. What counts is the power in the
// bands the profile's receiver listens to: nava's two tones (each within half its bit rate),
// the room profile's whole band. A recording whose power lies in those bands hurts more than
// white noise of the same full-band level; one that rumbles below them, less. No ROS.
#include <cstddef>
#include <utility>
#include <vector>

#include "nava_modem/modem_profile.h"

namespace nava_modem {

// Frequency bands, Hz, [low, high).
using Bands = std::vector<std::pair<double, double>>;

// The bands `profile`'s receiver listens in, with the thesis's tones for nava.
Bands ListeningBands(Profile profile);

class RecordedNoise {
 public:
  // Welch's method: Hann windows of kWindow samples, half overlapping, their power spectra
  // averaged. Throws std::invalid_argument for a sample rate not above 0, a recording shorter
  // than one window, a sample that is not finite, or a silent recording.
  RecordedNoise(const std::vector<float>& samples, double sample_rate);

  static constexpr std::size_t kWindow = 4096;

  double sample_rate() const { return sample_rate_; }
  double power() const { return power_; }  // mean square over the whole band
  // The fraction of the power within `bands` (the part of a bin inside a band counts).
  double Fraction(const Bands& bands) const;

 private:
  double sample_rate_;
  double power_ = 0.0;
  std::vector<double> density_;  // per bin of sample_rate / kWindow Hz, summing to 1
};

// The fraction of white noise's power, sampled at `sample_rate`, within `bands`.
double WhiteFraction(const Bands& bands, double sample_rate);

// What to add to a recording's full-band SNR to read it as white noise sampled at `white_rate`
// (the decode table's rate) with the same power in `bands`: 10 log10(white's fraction / the
// recording's). Positive for a noise that mostly misses the bands.
double WhiteEquivalentOffsetDb(const RecordedNoise& noise, const Bands& bands, double white_rate);

}  // namespace nava_modem
