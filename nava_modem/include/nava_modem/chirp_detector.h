#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

namespace nava_modem {

class NoiseSpectrum;

struct ChirpDetectorOptions {
  // A peak of the matched filter's output power counts as a chirp when it exceeds the mean
  // output over the preceding `background_seconds` by this factor (CFAR). Noise alone gives
  // exponentially distributed power: a factor of 25 (14 dB) is passed by chance about once in
  // 10^11 samples; a chirp 10 dB under the reverberation still gives several hundred.
  double threshold = 25.0;
  double background_seconds = 0.3;
  double guard_seconds = 0.02;  // the background ends this long before the sample judged
  // After the threshold is passed, the strongest output is the chirp once nothing stronger has
  // come for this long (the direct sound may be followed by reflections; a stronger one is
  // taken, the same one in both chirps of a packet).
  double peak_window_seconds = 0.02;
  // Envelope kept for looking back (pairing chirps, refining their distance).
  double history_seconds = 2.5;
  // The input is whitened by the noise's spectrum before the matched filter (NoiseSpectrum:
  // the least power at each frequency over about this long).
  double whitening_seconds = 3.0;
};

// Throws std::invalid_argument "chirp detector <field> <value>: expected ..." when the options
// are impossible: a threshold not above 1 (every sample would pass), a background, history or
// whitening time not above 0 s, a negative guard or peak window, any value not finite.
void ValidateChirpDetectorOptions(const ChirpDetectorOptions& options);

struct ChirpPeak {
  double sample = 0.0;    // where the chirp starts, in samples since the first (sub-sample)
  double ratio = 0.0;     // peak power over the background
  double power = 0.0;     // peak output power
};

// A matched filter for one known chirp over an endless stream, by FFT overlap-save (FFTW), on
// the input whitened by the noise's spectrum, with the analytic (complex) output so that its
// magnitude is the envelope, and CFAR peak picking on the envelope's power.
class ChirpDetector {
 public:
  // Throws std::invalid_argument for an empty chirp, a sample rate outside the project's range
  // (ValidateSampleRate) or impossible options (ValidateChirpDetectorOptions).
  ChirpDetector(const std::vector<float>& chirp, double sample_rate, const ChirpDetectorOptions& options);
  ~ChirpDetector();
  ChirpDetector(const ChirpDetector&) = delete;
  ChirpDetector& operator=(const ChirpDetector&) = delete;

  // Feeds samples; appends the chirps found (each once, a peak window after it).
  void Process(const float* samples, std::size_t count, std::vector<ChirpPeak>& peaks);
  // No detections before sample `until` (muting).
  void Blank(std::int64_t until) {
    blank_until_ = std::max(blank_until_, until);
    echo_until_ = std::min(echo_until_, blank_until_);
  }
  // The matched filter's output power at chirp start `n`, if still kept (0 otherwise).
  double Envelope(std::int64_t n) const;
  // Output known up to (not including) this chirp start.
  std::int64_t computed() const { return computed_; }
  std::size_t length() const { return chirp_length_; }

 private:
  void RunBlock();
  void Judge(std::int64_t n, double p, std::vector<ChirpPeak>& peaks);

  ChirpDetectorOptions options_;
  std::size_t chirp_length_, fft_size_, hop_, margin_;
  double template_energy_, template_spectrum_energy_;
  std::unique_ptr<NoiseSpectrum> noise_;
  std::vector<double> power_, gain_;  // per bin: this block's power, the whitening gains
  struct Fft;  // the block's transforms and the chirp's spectrum
  std::unique_ptr<Fft> fft_;
  std::vector<double> input_;        // the last fft_size_ samples
  std::size_t input_fill_ = 0;       // samples in input_ not yet run through a block
  std::int64_t block_start_ = 0;     // absolute index of input_[0]
  std::vector<float> envelope_;      // ring of output power by chirp start
  std::size_t envelope_mask_;
  std::int64_t computed_ = 0;
  // CFAR state: the background is a running sum over the envelope ring.
  double background_sum_ = 0.0;
  std::int64_t background_len_, guard_len_, peak_len_;
  std::int64_t blank_until_ = 0;
  // After a chirp, its reflections for a chirp's length: only a stronger peak counts then (the
  // next chirp can follow a false alarm closely).
  std::int64_t echo_until_ = 0;
  double echo_power_ = 0.0;
  bool peaking_ = false;
  ChirpPeak best_{};
  std::int64_t peak_deadline_ = 0;
};

}  // namespace nava_modem
