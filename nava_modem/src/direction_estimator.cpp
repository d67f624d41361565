#include "nava_modem/direction_estimator.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "nava_modem/parabola.h"

namespace nava_modem {
namespace {

using Complex = std::complex<double>;

// Collinear arrays: a delay under this fraction of the largest cannot say which end the sound
// is nearer (within 11.5 degrees of broadside noise and reflections decide the sign).
constexpr double kBroadside = 0.2;
// An array whose microphones stray from their best line by under 1 % of its length is taken as
// collinear: the delays that would tell its two sides apart are then below the noise.
constexpr double kCollinear = 0.01;
// The band must hold this many bins of the analysis.
constexpr std::size_t kMinBandBins = 4;
constexpr double kSamepoint = 1e-6;  // m
constexpr int kBearingSteps = 360;    // 1 degree
constexpr int kAxisSteps = 200;       // cosine to the axis, from -1 to 1 in steps of 0.01

std::string Number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
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
BandLayout LayoutFor(const DirectionOptions& o) {
  return BandLayoutFor(o.sample_rate, o.low_hz, o.high_hz, LargestSpacing(o.mics) / o.speed_of_sound);
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
  const BandLayout a = LayoutFor(o);
  if (a.high_bin < a.low_bin + kMinBandBins - 1) {
    throw std::invalid_argument(context + ": band " + Number(o.low_hz) + "-" + Number(o.high_hz) + " Hz; expected at least " +
                                Number(kMinBandBins * a.bin_hz) + " Hz wide (" + std::to_string(kMinBandBins) +
                                " bins of the " + Number(a.bin_hz) + " Hz analysis)");
  }
}

DirectionEstimator::DirectionEstimator(const DirectionOptions& options)
    : options_((ValidateDirectionOptions(options), options)),
      welch_(LayoutFor(options_), static_cast<std::size_t>(std::lround(options_.max_seconds * options_.sample_rate))),
      gcc_(welch_.layout(), options_.sample_rate, options_.high_hz, LargestSpacing(options_.mics) / options_.speed_of_sound) {
  const DirectionOptions& o = options_;
  const double largest = LargestSpacing(o.mics);

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

  for (int g = 0; g < kBearingSteps; ++g) {
    grid_x_.push_back(std::cos(2.0 * M_PI * g / kBearingSteps));
    grid_y_.push_back(std::sin(2.0 * M_PI * g / kBearingSteps));
  }
}

DirectionEstimator::~DirectionEstimator() = default;

double DirectionEstimator::Tdoa(const float* i, const float* j, std::size_t count) const {
  const PairCorrelation r = gcc_.Correlate(welch_.Analyse({i, j}, count), 0, 1);
  if (r.used == 0) return std::numeric_limits<double>::quiet_NaN();
  const auto best = std::max_element(r.lags.begin(), r.lags.end()) - r.lags.begin();
  double step = static_cast<double>(best);
  if (best > 0 && best + 1 < static_cast<std::ptrdiff_t>(r.lags.size())) {
    step += ParabolaOffset(r.lags[best - 1], r.lags[best], r.lags[best + 1]);
  }
  return (step - static_cast<double>(r.half)) / static_cast<double>(gcc_.interpolation()) / options_.sample_rate;
}

Direction DirectionEstimator::Estimate(const std::vector<const float*>& channels, std::size_t count) const {
  const std::vector<Microphone2D>& mics = options_.mics;
  if (channels.size() != mics.size()) {
    throw std::invalid_argument("DirectionEstimator::Estimate: " + std::to_string(channels.size()) + " channels for " +
                                std::to_string(mics.size()) + " microphones");
  }
  const BandSpectra s = welch_.Analyse(channels, count);
  struct Pair {
    PairCorrelation correlation;
    double dx, dy;  // (mic i - mic j) / c: the pair's delay (s) for a unit direction towards the source
  };
  std::vector<Pair> pairs;
  bool heard = false;
  for (std::size_t i = 0; i < mics.size(); ++i) {
    for (std::size_t j = i + 1; j < mics.size(); ++j) {
      pairs.push_back({gcc_.Correlate(s, i, j), (mics[i].x - mics[j].x) / options_.speed_of_sound,
                       (mics[i].y - mics[j].y) / options_.speed_of_sound});
      heard = heard || pairs.back().correlation.used > 0;
    }
  }
  if (!heard) return {};

  const double steps = options_.sample_rate * static_cast<double>(gcc_.interpolation());  // lag steps per second
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
    for (int g = 0; g < kBearingSteps; ++g) grid[g] = power(grid_x_[g], grid_y_[g]);
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
  const double bin_radians = 2.0 * M_PI * options_.sample_rate / static_cast<double>(welch_.layout().segment);
  for (const Pair& p : pairs) {
    const double delay = p.dx * ux + p.dy * uy;
    // e^{jwt} bin by bin as a rotating phasor: two sincos per pair instead of one per bin.
    Complex turn = std::polar(1.0, bin_radians * static_cast<double>(welch_.layout().low_bin) * delay);
    const Complex step = std::polar(1.0, bin_radians * delay);
    for (std::size_t b = 0; b < s.bins; ++b, turn *= step) coherent += (p.correlation.cross[b] * turn).real();
    total += p.correlation.power;
  }
  d.confidence = total > 0.0 ? std::clamp(coherent / total, 0.0, 1.0) : 0.0;
  return d;
}

}  // namespace nava_modem
