#include "nava_modem/band_spectra.h"

#include <algorithm>
#include <cmath>

#include "nava_modem/fft_plan.h"
#include "nava_modem/power_of_two.h"

namespace nava_modem {
namespace {

using Complex = std::complex<double>;

constexpr double kSegmentSeconds = 0.02;  // see BandLayout
constexpr double kTaper = 0.25;
// Segments per channel at most: the cost's bound. Beyond it they are spread over the samples
// with gaps between them, which keeps the variety of a long signal (the nava profile's two
// tones and its data bits) at a fraction of the FFTs.
constexpr std::size_t kMaxSegments = 8;

// A Tukey window: flat, with raised-cosine ends of kTaper / 2 of its length each. Segments do
// not overlap (that would double the FFTs), so the flat middle keeps most of each sample's
// weight, while the tapers keep the band's edges from leaking.
std::vector<double> Window(std::size_t n) {
  std::vector<double> w(n, 1.0);
  const double ramp = std::max(1.0, kTaper / 2.0 * static_cast<double>(n));
  for (std::size_t k = 0; k < n && static_cast<double>(k) < ramp; ++k) {
    w[k] = w[n - 1 - k] = 0.5 - 0.5 * std::cos(M_PI * (static_cast<double>(k) + 0.5) / ramp);
  }
  return w;
}

}  // namespace

BandLayout BandLayoutFor(double sample_rate, double low_hz, double high_hz, double max_delay) {
  BandLayout a;
  a.segment = PowerOfTwoAtLeast(std::max({kSegmentSeconds * sample_rate, 8.0 * max_delay * sample_rate, 16.0}));
  a.bin_hz = sample_rate / static_cast<double>(a.segment);
  a.low_bin = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(low_hz / a.bin_hz)));
  a.high_bin = std::min(a.segment / 2, static_cast<std::size_t>(std::floor(high_hz / a.bin_hz)));
  return a;
}

// Analyse() may run on several threads at once: each call executes the plan on arrays of its
// own (FftPlan::MakeBuffers), so the plan is made once and never locked.
struct WelchAnalyser::Plan {
  std::vector<double> window;  // over a whole segment
  FftPlan forward;
  explicit Plan(std::size_t segment) : window(Window(segment)), forward(FftKind::kRealToComplex, segment) {}
};

WelchAnalyser::WelchAnalyser(const BandLayout& layout, std::size_t max_samples)
    : layout_(layout), max_samples_(max_samples), plan_(std::make_shared<const Plan>(layout.segment)) {}

BandSpectra WelchAnalyser::Analyse(const std::vector<const float*>& channels, std::size_t count) const {
  const std::size_t segment = layout_.segment;
  const std::size_t n = std::min(count, max_samples_);
  BandSpectra s;
  s.bins = layout_.high_bin - layout_.low_bin + 1;
  std::vector<std::size_t> starts;
  if (n > 0 && n <= segment) {
    starts.push_back(0);
  } else if (n > segment) {
    // Back to back if they fit, else kMaxSegments spread evenly from the first sample to the last.
    const std::size_t fit = (n + segment - 1) / segment;
    const std::size_t count_of = std::min(fit, kMaxSegments);
    for (std::size_t g = 0; g < count_of; ++g) starts.push_back(g * (n - segment) / (count_of - 1));
  }
  s.segments = starts.size();
  // A short input gets a window of its own length, zero-padded to a segment.
  std::vector<double> short_window;
  if (n > 0 && n < segment) short_window = Window(n);
  const std::vector<double>& window = short_window.empty() ? plan_->window : short_window;
  const std::size_t length = std::min(n, segment);

  FftBuffers buffers = plan_->forward.MakeBuffers();
  double* in = buffers.real_input();
  const Complex* out = buffers.complex_output();
  s.channel.resize(channels.size());
  s.power.assign(channels.size(), std::vector<double>(s.bins, 0.0));
  for (std::size_t c = 0; c < channels.size(); ++c) {
    s.channel[c].resize(s.segments * s.bins);
    for (std::size_t g = 0; g < s.segments; ++g) {
      const float* x = channels[c] + starts[g];
      for (std::size_t k = 0; k < length; ++k) in[k] = window[k] * x[k];
      std::fill(in + length, in + segment, 0.0);
      plan_->forward.Execute(buffers);
      for (std::size_t b = 0; b < s.bins; ++b) {
        const Complex& v = out[layout_.low_bin + b];
        s.channel[c][g * s.bins + b] = v;
        s.power[c][b] += v.real() * v.real() + v.imag() * v.imag();
      }
    }
  }
  return s;
}

}  // namespace nava_modem
