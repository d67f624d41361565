#include "nava_modem/direction_estimator.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "nava_modem/fft_plan.h"
#include "nava_modem/parabola.h"
#include "nava_modem/power_of_two.h"

namespace nava_modem {
namespace {

using Complex = std::complex<double>;

// Cross-power this far under the band's strongest bin is taken for noise and left out of the
// PHAT sum (40 dB): the nava profile puts its energy in two tones and PHAT would give every
// empty bin the weight of a tone.
constexpr double kWeakBin = 1e-4;
// Collinear arrays: a delay under this fraction of the largest cannot say which end the sound
// is nearer (within 11.5 degrees of broadside noise and reflections decide the sign).
constexpr double kBroadside = 0.2;
// An array whose microphones stray from their best line by under 1 % of its length is taken as
// collinear: the delays that would tell its two sides apart are then below the noise.
constexpr double kCollinear = 0.01;
// Welch segments: long enough for bins of 50 Hz or finer and for 8 times the largest delay
// (the correlation's lags must not wrap), short enough to average several in 0.12 s.
constexpr double kSegmentSeconds = 0.02;
constexpr std::size_t kMinBandBins = 4;
constexpr double kTaper = 0.25;
// Segments per channel at most: the cost's bound. Beyond it they are spread over the samples
// with gaps between them, which keeps the variety of a long signal (the nava profile's two
// tones and its data bits) at a fraction of the FFTs.
constexpr std::size_t kMaxSegments = 8;
constexpr double kSamepoint = 1e-6;  // m
constexpr int kBearingSteps = 360;    // 1 degree
constexpr int kAxisSteps = 200;       // cosine to the axis, from -1 to 1 in steps of 0.01

std::string Number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

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

// An angle in (-pi, pi].
double Bearing(double y, double x) {
  const double a = std::atan2(y, x);
  return a <= -M_PI ? M_PI : a;
}

// An array on a robot spans centimetres to a metre or two; farther is a typo (and would ask the
// correlations for absurd lengths).
constexpr double kFarthestMicrophone = 10.0;

void CheckDistinct(const std::vector<Microphone2D>& mics, const std::string& context) {
  for (std::size_t i = 0; i < mics.size(); ++i) {
    for (std::size_t j = i + 1; j < mics.size(); ++j) {
      if (std::hypot(mics[i].x - mics[j].x, mics[i].y - mics[j].y) < kSamepoint) {
        throw std::invalid_argument(context + ": microphones " + std::to_string(i + 1) + " and " + std::to_string(j + 1) +
                                    " are both at (" + Number(mics[i].x) + ", " + Number(mics[i].y) +
                                    "); expected distinct positions");
      }
    }
  }
}

}  // namespace

std::vector<Microphone2D> ParseMicPositions(const std::string& text) {
  const std::string context = "microphone positions '" + text + "'";
  std::vector<double> values;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = text.find(',', begin);
    const std::string item = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    const char* tail = end;
    const bool blank_tail = tail && std::all_of(tail, item.c_str() + item.size(), [](char c) { return c == ' '; });
    if (item.find_first_not_of(' ') == std::string::npos || !blank_tail || !std::isfinite(v)) {
      throw std::invalid_argument(context + ": '" + item + "' is not a number; expected x1,y1,x2,y2,... in metres");
    }
    values.push_back(v);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  if (values.size() % 2 != 0) {
    throw std::invalid_argument(context + ": " + std::to_string(values.size()) +
                                " numbers; expected an x,y pair per microphone");
  }
  if (values.size() < 4) {
    throw std::invalid_argument(context + ": 1 microphone; expected at least 2");
  }
  std::vector<Microphone2D> mics;
  for (std::size_t k = 0; k < values.size(); k += 2) mics.push_back({values[k], values[k + 1]});
  for (const Microphone2D& m : mics) {
    if (std::abs(m.x) > kFarthestMicrophone || std::abs(m.y) > kFarthestMicrophone) {
      throw std::invalid_argument(context + ": (" + Number(m.x) + ", " + Number(m.y) + "): expected within " +
                                  Number(kFarthestMicrophone) + " m of the robot's origin");
    }
  }
  CheckDistinct(mics, context);
  return mics;
}

struct DirectionEstimator::Fft {
  std::size_t segment = 0, inverse = 0;
  std::vector<double> window;  // over a whole segment
  std::vector<double> grid_x, grid_y;  // the bearing grid's unit vectors
  // Estimate() is const and may run on several threads at once: each call executes these on
  // arrays of its own (FftPlan::MakeBuffers), so the plans are made once and never locked.
  FftPlan forward, backward;

  Fft(std::size_t segment_size, std::size_t inverse_size)
      : segment(segment_size),
        inverse(inverse_size),
        forward(FftKind::kRealToComplex, segment_size),
        backward(FftKind::kComplexToReal, inverse_size) {
    window = Window(segment);
    for (int g = 0; g < kBearingSteps; ++g) {
      grid_x.push_back(std::cos(2.0 * M_PI * g / kBearingSteps));
      grid_y.push_back(std::sin(2.0 * M_PI * g / kBearingSteps));
    }
  }
};

struct DirectionEstimator::Spectra {
  std::size_t bins = 0, segments = 0;
  std::vector<std::vector<Complex>> channel;  // [channel][segment * bins + band bin]
  std::vector<std::vector<double>> power;     // [channel][band bin], summed over segments
};

struct DirectionEstimator::Correlation {
  std::vector<Complex> cross;  // Welch-averaged conj(X_i) X_j per band bin
  double power = 0.0;          // sum over band bins of sqrt(S_ii S_jj): what `cross` could be at most
  std::size_t used = 0;        // bins in the PHAT sum
  std::ptrdiff_t half = 0;     // lags[m] is at lag (m - half) steps
  std::vector<double> lags;    // GCC-PHAT, 1 for a clean delay

  double At(double step) const {
    const double x = std::clamp(step + static_cast<double>(half), 0.0, static_cast<double>(lags.size() - 1));
    const std::size_t k = std::min(static_cast<std::size_t>(x), lags.size() - 2);
    const double f = x - static_cast<double>(k);
    return lags[k] * (1.0 - f) + lags[k + 1] * f;
  }
};

namespace {

double LargestSpacing(const std::vector<Microphone2D>& mics) {
  double largest = 0.0;
  for (std::size_t i = 0; i < mics.size(); ++i) {
    for (std::size_t j = i + 1; j < mics.size(); ++j) {
      largest = std::max(largest, std::hypot(mics[i].x - mics[j].x, mics[i].y - mics[j].y));
    }
  }
  return largest;
}

// The analysis the options ask for: Welch segment length and the band's bins in it.
struct Analysis {
  std::size_t segment = 0;
  std::size_t low_bin = 0, high_bin = 0;  // inclusive
  double bin_hz = 0.0;
};

Analysis AnalysisFor(const DirectionOptions& o) {
  Analysis a;
  const double max_delay = LargestSpacing(o.mics) / o.speed_of_sound;
  a.segment = PowerOfTwoAtLeast(std::max({kSegmentSeconds * o.sample_rate, 8.0 * max_delay * o.sample_rate, 16.0}));
  a.bin_hz = o.sample_rate / static_cast<double>(a.segment);
  a.low_bin = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(o.low_hz / a.bin_hz)));
  a.high_bin = std::min(a.segment / 2, static_cast<std::size_t>(std::floor(o.high_hz / a.bin_hz)));
  return a;
}

}  // namespace

void ValidateDirectionOptions(const DirectionOptions& o) {
  const std::string context = "DirectionOptions";
  if (o.mics.size() < 2) {
    throw std::invalid_argument(context + ": " + std::to_string(o.mics.size()) + " microphones; expected at least 2");
  }
  for (const Microphone2D& m : o.mics) {
    if (!std::isfinite(m.x) || !std::isfinite(m.y)) {
      throw std::invalid_argument(context + ": microphone at (" + Number(m.x) + ", " + Number(m.y) + "); expected finite metres");
    }
  }
  CheckDistinct(o.mics, context);
  if (!(o.sample_rate > 0.0) || !std::isfinite(o.sample_rate)) {
    throw std::invalid_argument(context + ": sample_rate " + Number(o.sample_rate) + " Hz; expected above 0");
  }
  if (!(o.speed_of_sound > 0.0) || !std::isfinite(o.speed_of_sound)) {
    throw std::invalid_argument(context + ": speed_of_sound " + Number(o.speed_of_sound) + " m/s; expected above 0");
  }
  if (!(o.max_seconds > 0.0)) {
    throw std::invalid_argument(context + ": max_seconds " + Number(o.max_seconds) + " s; expected above 0");
  }
  if (!(o.high_hz > 0.0) || o.high_hz > o.sample_rate / 2.0) {
    throw std::invalid_argument(context + ": high_hz " + Number(o.high_hz) + " Hz; expected above 0 and at most " +
                                Number(o.sample_rate / 2.0) + " Hz (half the sample rate)");
  }
  if (!(o.low_hz >= 0.0) || !(o.low_hz < o.high_hz)) {
    throw std::invalid_argument(context + ": low_hz " + Number(o.low_hz) + " Hz; expected from 0 to below high_hz " +
                                Number(o.high_hz) + " Hz");
  }
  const Analysis a = AnalysisFor(o);
  if (a.high_bin < a.low_bin + kMinBandBins - 1) {
    throw std::invalid_argument(context + ": band " + Number(o.low_hz) + "-" + Number(o.high_hz) + " Hz; expected at least " +
                                Number(kMinBandBins * a.bin_hz) + " Hz wide (" + std::to_string(kMinBandBins) +
                                " bins of the " + Number(a.bin_hz) + " Hz analysis)");
  }
}

DirectionEstimator::DirectionEstimator(const DirectionOptions& options) : options_(options) {
  const DirectionOptions& o = options_;
  ValidateDirectionOptions(o);
  const double largest = LargestSpacing(o.mics);
  max_delay_ = largest / o.speed_of_sound;

  // The array's best line (principal axis through the centroid) and how far the mics stray.
  double cx = 0.0, cy = 0.0;
  for (const Microphone2D& m : o.mics) {
    cx += m.x / o.mics.size();
    cy += m.y / o.mics.size();
  }
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const Microphone2D& m : o.mics) {
    sxx += (m.x - cx) * (m.x - cx);
    sxy += (m.x - cx) * (m.y - cy);
    syy += (m.y - cy) * (m.y - cy);
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  axis_x_ = std::cos(angle);
  axis_y_ = std::sin(angle);
  double off_line = 0.0;
  for (const Microphone2D& m : o.mics) off_line = std::max(off_line, std::abs(-(m.x - cx) * axis_y_ + (m.y - cy) * axis_x_));
  collinear_ = off_line <= kCollinear * largest;

  const Analysis a = AnalysisFor(o);
  segment_ = a.segment;
  interpolation_ = PowerOfTwoAtLeast(8.0 * o.high_hz / o.sample_rate);
  low_bin_ = a.low_bin;
  high_bin_ = a.high_bin;
  fft_ = std::make_shared<const Fft>(segment_, segment_ * interpolation_);
}

DirectionEstimator::~DirectionEstimator() = default;

DirectionEstimator::Spectra DirectionEstimator::Analyse(const std::vector<const float*>& channels,
                                                        std::size_t count) const {
  const std::size_t n = std::min(count, static_cast<std::size_t>(std::lround(options_.max_seconds * options_.sample_rate)));
  Spectra s;
  s.bins = high_bin_ - low_bin_ + 1;
  std::vector<std::size_t> starts;
  if (n > 0 && n <= segment_) {
    starts.push_back(0);
  } else if (n > segment_) {
    // Back to back if they fit, else kMaxSegments spread evenly from the first sample to the last.
    const std::size_t fit = (n + segment_ - 1) / segment_;
    const std::size_t count_of = std::min(fit, kMaxSegments);
    for (std::size_t g = 0; g < count_of; ++g) starts.push_back(g * (n - segment_) / (count_of - 1));
  }
  s.segments = starts.size();
  // A short input gets a window of its own length, zero-padded to a segment.
  std::vector<double> short_window;
  if (n > 0 && n < segment_) short_window = Window(n);
  const std::vector<double>& window = short_window.empty() ? fft_->window : short_window;
  const std::size_t length = std::min(n, segment_);

  FftBuffers buffers = fft_->forward.MakeBuffers();
  double* in = buffers.real_input();
  const std::complex<double>* out = buffers.complex_output();
  s.channel.resize(channels.size());
  s.power.assign(channels.size(), std::vector<double>(s.bins, 0.0));
  for (std::size_t c = 0; c < channels.size(); ++c) {
    s.channel[c].resize(s.segments * s.bins);
    for (std::size_t g = 0; g < s.segments; ++g) {
      const float* x = channels[c] + starts[g];
      for (std::size_t k = 0; k < length; ++k) in[k] = window[k] * x[k];
      std::fill(in + length, in + segment_, 0.0);
      fft_->forward.Execute(buffers);
      for (std::size_t b = 0; b < s.bins; ++b) {
        const Complex& v = out[low_bin_ + b];
        s.channel[c][g * s.bins + b] = v;
        s.power[c][b] += v.real() * v.real() + v.imag() * v.imag();
      }
    }
  }
  return s;
}

DirectionEstimator::Correlation DirectionEstimator::Correlate(const Spectra& s, std::size_t i, std::size_t j) const {
  Correlation r;
  r.cross.assign(s.bins, Complex(0.0, 0.0));
  for (std::size_t g = 0; g < s.segments; ++g) {
    const Complex* xi = s.channel[i].data() + g * s.bins;
    const Complex* xj = s.channel[j].data() + g * s.bins;
    for (std::size_t b = 0; b < s.bins; ++b) r.cross[b] += std::conj(xi[b]) * xj[b];
  }
  std::vector<double> magnitude(s.bins);
  double strongest = 0.0;
  for (std::size_t b = 0; b < s.bins; ++b) {
    r.power += std::sqrt(s.power[i][b] * s.power[j][b]);
    magnitude[b] = std::sqrt(std::norm(r.cross[b]));
    strongest = std::max(strongest, magnitude[b]);
  }

  const std::size_t inverse = fft_->inverse;
  const double steps_per_sample = static_cast<double>(interpolation_);
  r.half = std::min<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(std::ceil((max_delay_ * options_.sample_rate + 2.0) * steps_per_sample)),
                                    static_cast<std::ptrdiff_t>(inverse / 2 - 1));
  r.lags.assign(static_cast<std::size_t>(2 * r.half + 1), 0.0);
  if (strongest <= 0.0) return r;

  // Fresh buffers start zeroed: the bins outside the band stay so.
  FftBuffers buffers = fft_->backward.MakeBuffers();
  Complex* bins = buffers.complex_input();
  for (std::size_t b = 0; b < s.bins; ++b) {
    if (magnitude[b] <= kWeakBin * strongest) continue;
    // Same bin index in the longer inverse transform = same frequency: the zero padding
    // interpolates the lags by `interpolation_`.
    bins[low_bin_ + b] = Complex(r.cross[b].real() / magnitude[b], r.cross[b].imag() / magnitude[b]);
    ++r.used;
  }
  fft_->backward.Execute(buffers);
  const double* lags = buffers.real_output();
  // c2r counts each bin with its mirror: a clean delay peaks at 2 x used.
  const double scale = 1.0 / (2.0 * static_cast<double>(r.used));
  for (std::ptrdiff_t m = -r.half; m <= r.half; ++m) {
    const std::size_t at = static_cast<std::size_t>((m + static_cast<std::ptrdiff_t>(inverse)) % static_cast<std::ptrdiff_t>(inverse));
    r.lags[static_cast<std::size_t>(m + r.half)] = lags[at] * scale;
  }
  return r;
}

double DirectionEstimator::Tdoa(const float* i, const float* j, std::size_t count) const {
  const Spectra s = Analyse({i, j}, count);
  const Correlation r = Correlate(s, 0, 1);
  if (r.used == 0) return std::numeric_limits<double>::quiet_NaN();
  const auto best = std::max_element(r.lags.begin(), r.lags.end()) - r.lags.begin();
  double step = static_cast<double>(best);
  if (best > 0 && best + 1 < static_cast<std::ptrdiff_t>(r.lags.size())) {
    step += ParabolaOffset(r.lags[best - 1], r.lags[best], r.lags[best + 1]);
  }
  return (step - static_cast<double>(r.half)) / static_cast<double>(interpolation_) / options_.sample_rate;
}

Direction DirectionEstimator::Estimate(const std::vector<const float*>& channels, std::size_t count) const {
  const std::vector<Microphone2D>& mics = options_.mics;
  if (channels.size() != mics.size()) {
    throw std::invalid_argument("DirectionEstimator::Estimate: " + std::to_string(channels.size()) + " channels for " +
                                std::to_string(mics.size()) + " microphones");
  }
  const Spectra s = Analyse(channels, count);
  struct Pair {
    Correlation correlation;
    double dx, dy;  // (mic i - mic j) / c: the pair's delay (s) for a unit direction towards the source
  };
  std::vector<Pair> pairs;
  bool heard = false;
  for (std::size_t i = 0; i < mics.size(); ++i) {
    for (std::size_t j = i + 1; j < mics.size(); ++j) {
      pairs.push_back({Correlate(s, i, j), (mics[i].x - mics[j].x) / options_.speed_of_sound,
                       (mics[i].y - mics[j].y) / options_.speed_of_sound});
      heard = heard || pairs.back().correlation.used > 0;
    }
  }
  if (!heard) return {};

  const double steps = options_.sample_rate * static_cast<double>(interpolation_);  // lag steps per second
  // Steered response power for a unit direction (ux, uy) towards the source, far field.
  const auto power = [&](double ux, double uy) {
    double sum = 0.0;
    for (const Pair& p : pairs) sum += p.correlation.At((p.dx * ux + p.dy * uy) * steps);
    return sum;
  };

  Direction d;
  double ux = 0.0, uy = 0.0;  // the chosen direction, for the confidence
  if (!collinear_) {
    std::vector<double> grid(kBearingSteps);
    for (int g = 0; g < kBearingSteps; ++g) grid[g] = power(fft_->grid_x[g], fft_->grid_y[g]);
    const int best = static_cast<int>(std::max_element(grid.begin(), grid.end()) - grid.begin());
    const double offset = ParabolaOffset(grid[(best + kBearingSteps - 1) % kBearingSteps], grid[best],
                                         grid[(best + 1) % kBearingSteps]);
    const double theta = 2.0 * M_PI * (best + offset) / kBearingSteps;
    ux = std::cos(theta);
    uy = std::sin(theta);
    d.bearing = Bearing(uy, ux);
  } else {
    // Only the cosine to the axis shows in the delays: search it, then keep its sign.
    std::vector<double> grid(kAxisSteps + 1);
    const auto cosine = [](double g) { return -1.0 + 2.0 * g / kAxisSteps; };
    for (int g = 0; g <= kAxisSteps; ++g) grid[g] = power(cosine(g) * axis_x_, cosine(g) * axis_y_);
    const int best = static_cast<int>(std::max_element(grid.begin(), grid.end()) - grid.begin());
    const double offset = best > 0 && best < kAxisSteps ? ParabolaOffset(grid[best - 1], grid[best], grid[best + 1]) : 0.0;
    const double c = cosine(best + offset);
    if (std::abs(c) < kBroadside) return {};
    ux = c * axis_x_;
    uy = c * axis_y_;
    d.bearing = c > 0.0 ? Bearing(axis_y_, axis_x_) : Bearing(-axis_y_, -axis_x_);
  }

  double coherent = 0.0, total = 0.0;
  const double bin_radians = 2.0 * M_PI * options_.sample_rate / static_cast<double>(segment_);
  for (const Pair& p : pairs) {
    const double delay = p.dx * ux + p.dy * uy;
    // e^{jwt} bin by bin as a rotating phasor: two sincos per pair instead of one per bin.
    Complex turn = std::polar(1.0, bin_radians * static_cast<double>(low_bin_) * delay);
    const Complex step = std::polar(1.0, bin_radians * delay);
    for (std::size_t b = 0; b < s.bins; ++b, turn *= step) coherent += (p.correlation.cross[b] * turn).real();
    total += p.correlation.power;
  }
  d.confidence = total > 0.0 ? std::clamp(coherent / total, 0.0, 1.0) : 0.0;
  return d;
}

}  // namespace nava_modem
