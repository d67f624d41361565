#include "nava_modem/chirp_detector.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "nava_modem/fft_plan.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/noise_spectrum.h"
#include "nava_modem/parabola.h"
#include "nava_modem/power_of_two.h"

namespace nava_modem {
namespace {

// Output power (a chirp of amplitude A gives A^2) below which nothing counts: -80 dB, digital
// silence and dither.
constexpr double kFloor = 1e-8;
// The noise spectrum is smoothed over this much either side: far wider than the room profile's
// 25 Hz tone spacing, whose comb would otherwise be pressed into the chirp as false echoes 40 ms
// apart, and narrow against the band, so that a whine's neighbourhood is turned down.
constexpr double kSmoothHz = 250.0;
// How far the whitening's impulse response reaches either side (gains smooth over 500 Hz).
constexpr double kWhiteningSpan = 0.02;
// Renew the running background sum this often against rounding.
constexpr std::int64_t kRenewEvery = 1 << 16;

void Require(bool ok, const char* field, double value, const char* expected) {
  if (ok) return;
  std::ostringstream why;
  why << "chirp detector " << field << " " << value << ": expected " << expected;
  throw std::invalid_argument(why.str());
}

}  // namespace

void ValidateChirpDetectorOptions(const ChirpDetectorOptions& o) {
  Require(o.threshold > 1.0 && std::isfinite(o.threshold), "threshold", o.threshold,
          "a finite factor above 1 over the background");
  Require(o.background_seconds > 0.0 && std::isfinite(o.background_seconds), "background_seconds",
          o.background_seconds, "finite and above 0 s");
  Require(o.guard_seconds >= 0.0 && std::isfinite(o.guard_seconds), "guard_seconds", o.guard_seconds,
          "finite and at least 0 s");
  Require(o.peak_window_seconds >= 0.0 && std::isfinite(o.peak_window_seconds), "peak_window_seconds",
          o.peak_window_seconds, "finite and at least 0 s");
  Require(o.history_seconds > 0.0 && std::isfinite(o.history_seconds), "history_seconds", o.history_seconds,
          "finite and above 0 s");
  Require(o.whitening_seconds > 0.0 && std::isfinite(o.whitening_seconds), "whitening_seconds",
          o.whitening_seconds, "finite and above 0 s");
}

// The matched filter's two transforms for one block size: the block's spectrum, and back from
// the correlation's analytic spectrum (a complex transform, whose magnitude is the envelope).
struct ChirpDetector::Fft {
  explicit Fft(std::size_t n) : forward(FftKind::kRealToComplex, n), backward(FftKind::kComplexBackward, n) {}
  FftPlan forward, backward;
  std::vector<std::complex<double>> chirp_conj;  // conj(FFT of the zero-padded chirp), bins 0..n/2
};

ChirpDetector::ChirpDetector(const std::vector<float>& chirp, double sample_rate, const ChirpDetectorOptions& options)
    : options_(options), chirp_length_(chirp.size()) {
  if (chirp.empty()) throw std::invalid_argument("chirp detector: empty chirp");
  ValidateSampleRate("chirp detector sample rate", sample_rate);
  ValidateChirpDetectorOptions(options_);
  margin_ = static_cast<std::size_t>(std::ceil(kWhiteningSpan * sample_rate));
  fft_size_ = PowerOfTwoAtLeast(2.0 * (chirp_length_ + 2 * margin_));
  hop_ = fft_size_ - chirp_length_ - 2 * margin_ + 1;
  template_energy_ = 0.0;
  for (float c : chirp) template_energy_ += static_cast<double>(c) * c;
  fft_ = std::make_unique<Fft>(fft_size_);
  // The plan's input starts zeroed: the chirp is zero-padded to the block.
  std::copy(chirp.begin(), chirp.end(), fft_->forward.real_input());
  fft_->forward.Execute();
  const std::complex<double>* spectrum = fft_->forward.complex_output();
  fft_->chirp_conj.resize(fft_size_ / 2 + 1);
  template_spectrum_energy_ = 0.0;
  for (std::size_t k = 0; k <= fft_size_ / 2; ++k) {
    fft_->chirp_conj[k] = std::conj(spectrum[k]);
    template_spectrum_energy_ += std::norm(fft_->chirp_conj[k]);
  }
  noise_ = std::make_unique<NoiseSpectrum>(
      fft_size_ / 2 + 1, static_cast<std::size_t>(std::ceil(kSmoothHz * fft_size_ / sample_rate)),
      static_cast<std::size_t>(std::ceil(options_.whitening_seconds * sample_rate / hop_)));
  power_.resize(fft_size_ / 2 + 1);
  gain_.resize(fft_size_ / 2 + 1);
  input_.assign(fft_size_, 0.0);
  const std::size_t ring = PowerOfTwoAtLeast(options_.history_seconds * sample_rate + fft_size_ +
                                             (options_.background_seconds + options_.guard_seconds) * sample_rate);
  envelope_.assign(ring, 0.0f);
  envelope_mask_ = ring - 1;
  background_len_ = std::max<std::int64_t>(1, std::llround(options_.background_seconds * sample_rate));
  guard_len_ = std::llround(options_.guard_seconds * sample_rate);
  peak_len_ = std::llround(options_.peak_window_seconds * sample_rate);
}

ChirpDetector::~ChirpDetector() = default;

double ChirpDetector::Envelope(std::int64_t n) const {
  if (n < 0 || n >= computed_ || computed_ - n > static_cast<std::int64_t>(envelope_.size())) return 0.0;
  return envelope_[static_cast<std::size_t>(n) & envelope_mask_];
}

void ChirpDetector::Process(const float* samples, std::size_t count, std::vector<ChirpPeak>& peaks) {
  while (count > 0) {
    const std::size_t take = std::min(count, fft_size_ - input_fill_);
    std::copy(samples, samples + take, input_.begin() + static_cast<std::ptrdiff_t>(input_fill_));
    input_fill_ += take;
    samples += take;
    count -= take;
    if (input_fill_ < fft_size_) break;
    RunBlock();
    for (std::size_t k = margin_; k < margin_ + hop_; ++k) {
      const std::int64_t n = block_start_ + static_cast<std::int64_t>(k);
      Judge(n, envelope_[static_cast<std::size_t>(n) & envelope_mask_], peaks);
    }
    // The next block starts a hop later; its first chirp_length_ - 1 samples are already here.
    std::copy(input_.begin() + static_cast<std::ptrdiff_t>(hop_), input_.end(), input_.begin());
    input_fill_ = fft_size_ - hop_;
    block_start_ += static_cast<std::int64_t>(hop_);
  }
}

void ChirpDetector::RunBlock() {
  Fft& f = *fft_;
  std::copy(input_.begin(), input_.end(), f.forward.real_input());
  f.forward.Execute();
  const std::complex<double>* spectrum = f.forward.complex_output();
  const std::size_t half = fft_size_ / 2;
  // Whitening by the noise heard before this block: each frequency weighs by the inverse of
  // its noise power, so a whine, a rumble or pink noise counts no more than white noise of the
  // same level. A floor at a thousandth of the mean keeps near-silent frequencies from being
  // blown up; the gains are normalised over the chirp's spectrum, so that the output keeps its
  // scale from block to block (the CFAR compares blocks) and only the noise's shape matters.
  const std::vector<double>& noise = noise_->noise();
  double mean = 0.0;
  for (double n : noise) mean += n;
  mean /= static_cast<double>(noise.size());
  double weighted = 0.0;
  for (std::size_t k = 0; k <= half; ++k) {
    gain_[k] = 1.0 / (noise[k] + 1e-3 * mean + 1e-30);
    weighted += std::norm(f.chirp_conj[k]) * gain_[k];
  }
  const double normal = weighted > 0.0 ? template_spectrum_energy_ / weighted : 1.0;
  for (std::size_t k = 0; k <= half; ++k) power_[k] = std::norm(spectrum[k]);
  noise_->Add(power_);
  // The correlation's analytic signal: positive frequencies doubled, negative ones dropped.
  std::complex<double>* analytic = f.backward.complex_input();
  for (std::size_t k = 0; k <= half; ++k) {
    analytic[k] = spectrum[k] * std::sqrt(gain_[k] * normal) * f.chirp_conj[k] * ((k == 0 || k == half) ? 1.0 : 2.0);
  }
  std::fill(analytic + half + 1, analytic + fft_size_, std::complex<double>(0.0, 0.0));
  f.backward.Execute();
  const std::complex<double>* output = f.backward.complex_output();
  // Lag k of the circular correlation, the chirp starting at block_start_ + k, is exact for
  // margin_ <= k <= fft_size_ - chirp_length_ - margin_: the whitening's (zero-phase) impulse
  // response lengthens the chirp by up to margin_ either side, and what is longer wraps around
  // the block (a chirp at a block's end would show up as false chirps at its start). Scaled so
  // that a chirp of amplitude A in white noise gives A^2.
  const double scale = 1.0 / (static_cast<double>(fft_size_) * template_energy_);
  for (std::size_t k = margin_; k < margin_ + hop_; ++k) {
    const double re = output[k].real() * scale, im = output[k].imag() * scale;
    const std::int64_t n = block_start_ + static_cast<std::int64_t>(k);
    envelope_[static_cast<std::size_t>(n) & envelope_mask_] = static_cast<float>(re * re + im * im);
  }
  computed_ = block_start_ + static_cast<std::int64_t>(margin_ + hop_);
}

void ChirpDetector::Judge(std::int64_t n, double p, std::vector<ChirpPeak>& peaks) {
  auto at = [&](std::int64_t k) { return k < 0 ? 0.0 : static_cast<double>(envelope_[static_cast<std::size_t>(k) & envelope_mask_]); };
  const std::int64_t newest = n - guard_len_;
  background_sum_ += at(newest) - at(newest - background_len_);
  if (n % kRenewEvery == 0) {
    background_sum_ = 0.0;
    for (std::int64_t k = newest - background_len_ + 1; k <= newest; ++k) background_sum_ += at(k);
  }
  // Early in the stream the background is what there is of it so far.
  const std::int64_t have = std::min(background_len_, std::max<std::int64_t>(0, newest + 1));
  const double background = std::max(background_sum_ / std::max<std::int64_t>(1, have), kFloor * 1e-3);
  if (peaking_) {
    // The strongest output until none stronger came for a peak window: the threshold may be
    // passed early on the way up (over silence, on the filter's skirt).
    if (p > best_.power) {
      best_ = {static_cast<double>(n), p / background, p};
      peak_deadline_ = n + peak_len_;
    }
    if (n < peak_deadline_) return;
    // Sub-sample position from a parabola through the peak and its neighbours.
    const std::int64_t m = static_cast<std::int64_t>(best_.sample);
    best_.sample += ParabolaOffset(at(m - 1), at(m), at(m + 1));
    peaks.push_back(best_);
    peaking_ = false;
    // The chirp's own reflections follow it for a while, weaker: they are not chirps of their own.
    echo_until_ = m + static_cast<std::int64_t>(chirp_length_);
    echo_power_ = best_.power;
    return;
  }
  // Until a quarter of the background has been heard, there is too little to compare with.
  if (n >= blank_until_ && (n >= echo_until_ || p > echo_power_) && have >= background_len_ / 4 && p > kFloor && p > options_.threshold * background) {
    peaking_ = true;
    best_ = {static_cast<double>(n), p / background, p};
    peak_deadline_ = n + peak_len_;
  }
}

}  // namespace nava_modem
