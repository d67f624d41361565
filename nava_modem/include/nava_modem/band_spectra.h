#pragma once

// The direction estimator's first stage (direction_estimator.h): each microphone's spectrum in
// the band, Welch-averaged over short segments, from which the pairs' cross-spectra are made
// (gcc_phat.h). No ROS.
#include <complex>
#include <cstddef>
#include <memory>
#include <vector>

namespace nava_modem {

// The analysis a band and an array ask for: segments a power of two long, long enough for bins
// of 50 Hz or finer and for 8 times the largest delay (the correlation's lags must not wrap),
// short enough to average several in 0.12 s; the band's bins in them.
struct BandLayout {
  std::size_t segment = 0;                // samples
  std::size_t low_bin = 0, high_bin = 0;  // the band, inclusive
  double bin_hz = 0.0;
};

// `max_delay`: the array's largest spacing over the speed of sound (s).
BandLayout BandLayoutFor(double sample_rate, double low_hz, double high_hz, double max_delay);

// One call's band spectra, per channel and segment.
struct BandSpectra {
  std::size_t bins = 0, segments = 0;
  std::vector<std::vector<std::complex<double>>> channel;  // [channel][segment * bins + band bin]
  std::vector<std::vector<double>> power;                  // [channel][band bin], summed over segments
};

// The Welch analysis: each channel cut into segments (Tukey-windowed, not overlapping), at most
// 8: back to back when they fit, else spread evenly over the samples, which keeps a long signal's
// variety (the nava packet's two tones and its data bits) at a bounded cost. Copies share the
// FFT plan; Analyse() is const and may run on several threads at once.
class WelchAnalyser {
 public:
  // `max_samples`: only the first this many samples of a call are used.
  WelchAnalyser(const BandLayout& layout, std::size_t max_samples);

  // The band spectra of `count` samples of each channel.
  BandSpectra Analyse(const std::vector<const float*>& channels, std::size_t count) const;
  const BandLayout& layout() const { return layout_; }

 private:
  struct Plan;  // the window and the forward FFT
  BandLayout layout_;
  std::size_t max_samples_;
  std::shared_ptr<const Plan> plan_;
};

}  // namespace nava_modem
