#include "behaviours/wanderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "grid/option_checks.h"

namespace behaviours {

void ValidateOptions(const WanderOptions& o) {
  grid::RequireAtLeast("wander cruise_speed (m/s)", o.cruise_speed, 0.0);
  grid::RequireAtLeast("wander turn_rate (rad/s)", o.turn_rate, 0.0);
  grid::RequireAtLeast("wander avoid_range (m)", o.avoid_range, 0.0);
  grid::RequireAbove("wander slow_range (m, above avoid_range)", o.slow_range, o.avoid_range);
  grid::RequireAtLeast("wander heading_change (rad/s)", o.heading_change, 0.0);
  grid::RequireAbove("wander heading_period (s)", o.heading_period, 0.0);
}

Wanderer::Wanderer(const WanderOptions& options, std::uint32_t seed)
    : options_(options), rng_(seed) {
  ValidateOptions(options_);
}

VelocityCommand Wanderer::Update(const std::vector<float>& ranges, double dt) {
  const int n = static_cast<int>(ranges.size());
  if (n == 0) return {};
  auto range = [&](int k) {
    const float r = ranges[((k % n) + n) % n];
    return std::isfinite(r) ? static_cast<double>(r) : std::numeric_limits<double>::infinity();
  };
  // "Ahead" is every ranger within 50 degrees of the heading.
  const int half = std::max(1, static_cast<int>(std::floor(n * 50.0 / 360.0)));
  double ahead = range(0);
  for (int k = 1; k <= half; ++k) ahead = std::min({ahead, range(k), range(-k)});
  double left = 0.0, right = 0.0;
  for (int k = 1; k < (n + 1) / 2; ++k) {
    left += std::min(range(k), 10.0);
    right += std::min(range(-k), 10.0);
  }

  if (ahead < options_.avoid_range) {
    // Keep turning the same way until clear, so the robot does not dither in corners.
    if (avoid_direction_ == 0) avoid_direction_ = left >= right ? 1 : -1;
    return {0.0, avoid_direction_ * options_.turn_rate};
  }
  avoid_direction_ = 0;

  until_change_ -= dt;
  if (until_change_ <= 0.0) {
    std::uniform_real_distribution<double> turn(-options_.heading_change, options_.heading_change);
    cruise_turn_ = turn(rng_);
    until_change_ = options_.heading_period;
  }
  const double slow = std::clamp((ahead - options_.avoid_range) /
                                     (options_.slow_range - options_.avoid_range), 0.3, 1.0);
  return {options_.cruise_speed * slow, cruise_turn_};
}

}  // namespace behaviours
