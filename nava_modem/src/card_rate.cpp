#include "nava_modem/card_rate.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace nava_modem {

CardRateTracker::CardRateTracker(const CardRateOptions& options) : options_(options) {
  const auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) throw std::invalid_argument(std::string("card rate: ") + name + " " + std::to_string(v) + ": expected above 0");
  };
  positive(options.nominal_rate, "nominal rate");
  positive(options.window, "window");
  positive(options.min_span, "min_span");
  positive(options.spacing, "spacing");
  if (options.min_span > options.window) {
    throw std::invalid_argument("card rate: min_span " + std::to_string(options.min_span) + " s: expected at most the window, " +
                                std::to_string(options.window) + " s");
  }
  if (!(options.max_error > 0.0 && options.max_error <= 0.05)) {
    throw std::invalid_argument("card rate: max_error " + std::to_string(options.max_error) + ": expected in (0, 0.05]");
  }
}

void CardRateTracker::Add(double seconds, std::int64_t frames) {
  if (!std::isfinite(seconds)) return;
  // A clock or a count that went back is a new card: start again.
  if (!points_.empty() && (seconds < points_.back().seconds || frames < points_.back().frames)) points_.clear();
  const auto ahead = [&](const Point& p) { return static_cast<double>(p.frames) - options_.nominal_rate * (p.seconds - bin_start_); };
  if (!points_.empty() && seconds - bin_start_ < options_.spacing) {
    if (ahead({seconds, frames}) > ahead(points_.back())) points_.back() = {seconds, frames};
    return;
  }
  bin_start_ = seconds;
  points_.push_back({seconds, frames});
  while (points_.back().seconds - points_.front().seconds > options_.window) points_.pop_front();
}

double CardRateTracker::rate_error() const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (points_.size() < 3 || points_.back().seconds - points_.front().seconds < options_.min_span) return nan;
  // Least squares, relative to the first point so that large clocks and counts keep their digits.
  const Point& o = points_.front();
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (const Point& p : points_) {
    const double x = p.seconds - o.seconds, y = static_cast<double>(p.frames - o.frames);
    n += 1.0, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double error = slope / options_.nominal_rate - 1.0;
  return std::isfinite(error) && std::abs(error) <= options_.max_error ? error : nan;
}

}  // namespace nava_modem
