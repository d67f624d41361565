#include "charging_demo/trail.h"

#include <algorithm>
#include <stdexcept>

#include "grid/option_checks.h"

namespace charging_demo {

void ValidateOptions(const TrailOptions& o) {
  grid::RequireAbove("trail spacing (m)", o.spacing, 0.0);
  if (o.capacity < 2) throw std::invalid_argument("trail capacity must be at least 2 crumbs");
}

Trail::Trail(const TrailOptions& options) : options_((ValidateOptions(options), options)) {}

void Trail::Visit(const Eigen::Vector2d& position, double time) {
  if (!crumbs_.empty() && (position - crumbs_.back().position).norm() < options_.spacing) return;
  crumbs_.push_back({position, time});
  if (crumbs_.size() > options_.capacity) {
    crumbs_.pop_front();
    ++first_;
  }
}

std::optional<std::uint64_t> Trail::LaidBy(double time) const {
  // Crumbs are laid in time order.
  const auto after = std::upper_bound(crumbs_.begin(), crumbs_.end(), time,
                                      [](double t, const Crumb& c) { return t < c.time; });
  if (after == crumbs_.begin()) return std::nullopt;
  return first_ + static_cast<std::uint64_t>(after - crumbs_.begin()) - 1;
}

std::optional<std::uint64_t> Trail::FurthestBack(std::uint64_t from, std::uint64_t to, const Eigen::Vector2d& here,
                                                 double reach,
                                                 const std::function<bool(const Eigen::Vector2d&)>& usable) const {
  if (crumbs_.empty()) return std::nullopt;
  from = std::min(from, newest());
  to = std::max(to, first_);
  for (std::uint64_t i = to; i <= from; ++i) {
    const Eigen::Vector2d& p = at(i).position;
    if ((p - here).norm() <= reach && usable(p)) return i;
  }
  return std::nullopt;
}

}  // namespace charging_demo
