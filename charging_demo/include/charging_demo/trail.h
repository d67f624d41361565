#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>

#include <Eigen/Core>

namespace charging_demo {

struct TrailOptions {
  double spacing = 0.3;           // m between crumbs
  std::size_t capacity = 20000;   // crumbs kept; the oldest go first (6 km at 0.3 m)
};

void ValidateOptions(const TrailOptions& options);

// The way the robot came, as crumbs laid every `spacing` metres in the odom frame, each with its
// time. A local map forgets what lies behind the robot; the trail does not, so a robot can go
// back to where it last saw something (a charger) the way it came, through doors its local map
// no longer shows. Crumbs have absolute indices that count up from 0 and stay valid until the
// crumb drops out of the capacity.
class Trail {
 public:
  struct Crumb {
    Eigen::Vector2d position{0.0, 0.0};
    double time = 0.0;
  };

  explicit Trail(const TrailOptions& options);

  // The robot is at `position` at `time`: a crumb is laid when it is `spacing` from the last.
  void Visit(const Eigen::Vector2d& position, double time);

  bool empty() const { return crumbs_.empty(); }
  std::uint64_t oldest() const { return first_; }
  std::uint64_t newest() const { return first_ + crumbs_.size() - 1; }  // only when not empty
  const Crumb& at(std::uint64_t index) const { return crumbs_[index - first_]; }
  // The newest crumb laid at or before `time`; nullopt when every crumb kept is younger.
  std::optional<std::uint64_t> LaidBy(double time) const;

  // Going back from crumb `from` towards crumb `to` (to <= from): the oldest crumb in [to, from]
  // within `reach` of `here` for which `usable` holds (the caller's check that it can get there
  // from here); nullopt when none is.
  std::optional<std::uint64_t> FurthestBack(std::uint64_t from, std::uint64_t to, const Eigen::Vector2d& here,
                                            double reach,
                                            const std::function<bool(const Eigen::Vector2d&)>& usable) const;

 private:
  TrailOptions options_;
  std::deque<Crumb> crumbs_;
  std::uint64_t first_ = 0;  // absolute index of crumbs_.front()
};

}  // namespace charging_demo
