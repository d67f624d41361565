#include "local_navigation/local_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "grid/option_checks.h"

namespace local_navigation {

using grid::RequireAbove;
using grid::RequireAtLeast;

void ValidateOptions(const LocalMapOptions& o) {
  if (o.size < 3 || o.size % 2 == 0 || o.size > 4001)
    throw std::invalid_argument("local map size must be odd and within 3..4001 cells, got " +
                                std::to_string(o.size));
  RequireAbove("local map resolution (m)", o.resolution, 0.0);
  RequireAbove("local map expiry (s)", o.expiry, 0.0);
  RequireAtLeast("local map expiry_step (s)", o.expiry_step, 0.0);
}

LocalMap::LocalMap(const LocalMapOptions& options)
    : options_(options),
      cells_((ValidateOptions(options), static_cast<std::size_t>(options.size) * options.size),
             CellState::kUnknown),
      seen_(cells_.size(), 0.0) {
  origin_ = -centre_cell();
}

Eigen::Vector2i LocalMap::CellOf(const Eigen::Vector2d& point) const {
  return Eigen::Vector2i(static_cast<int>(std::floor(point.x() / options_.resolution)),
                         static_cast<int>(std::floor(point.y() / options_.resolution))) -
         origin_;
}

Eigen::Vector2d LocalMap::CentreOf(const Eigen::Vector2i& cell) const {
  return ((cell + origin_).cast<double>() + Eigen::Vector2d::Constant(0.5)) * options_.resolution;
}

void LocalMap::Recentre(const Eigen::Vector2d& position) {
  const Eigen::Vector2i wanted = CellOf(position) + origin_ - centre_cell();
  if (placed_ && wanted == origin_) return;
  const Eigen::Vector2i shift = wanted - origin_;
  std::vector<CellState> cells(cells_.size(), CellState::kUnknown);
  std::vector<double> seen(seen_.size(), 0.0);
  if (placed_) {
    const int n = options_.size;
    for (int y = 0; y < n; ++y) {
      const int from_y = y + shift.y();
      if (from_y < 0 || from_y >= n) continue;
      for (int x = 0; x < n; ++x) {
        const int from_x = x + shift.x();
        if (from_x < 0 || from_x >= n) continue;
        const std::size_t to = static_cast<std::size_t>(y) * n + x;
        const std::size_t from = static_cast<std::size_t>(from_y) * n + from_x;
        cells[to] = cells_[from];
        seen[to] = seen_[from];
      }
    }
  }
  cells_.swap(cells);
  seen_.swap(seen);
  origin_ = wanted;
  placed_ = true;
}

void LocalMap::Set(const Eigen::Vector2i& cell, CellState state, double time) {
  if (!Inside(cell)) return;
  cells_[Index(cell)] = state;
  seen_[Index(cell)] = time;
}

const std::vector<LocalMap::Offset>& LocalMap::Offsets(int radius) {
  if (radius == offsets_radius_) return offsets_;
  offsets_.clear();
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      if ((dx == 0 && dy == 0) || dx * dx + dy * dy > radius * radius) continue;
      offsets_.push_back({std::atan2(dy, dx), std::hypot(dx, dy) * options_.resolution, {dx, dy}});
    }
  }
  std::sort(offsets_.begin(), offsets_.end(),
            [](const Offset& a, const Offset& b) { return a.angle < b.angle; });
  offsets_radius_ = radius;
  return offsets_;
}

void LocalMap::ClearSector(const Eigen::Vector2i& from, double lo, double hi, double length,
                           double time) {
  const auto by_angle = [](const Offset& o, double a) { return o.angle < a; };
  auto first = std::lower_bound(offsets_.begin(), offsets_.end(), lo, by_angle);
  const auto last = std::lower_bound(offsets_.begin(), offsets_.end(), hi, by_angle);
  for (; first != last; ++first) {
    if (first->distance > length) continue;
    const Eigen::Vector2i cell = from + first->cell;
    // Keep what a beam saw: a sector only clears cells that are not known occupied.
    if (Inside(cell) && cells_[Index(cell)] != CellState::kOccupied)
      Set(cell, CellState::kFree, time);
  }
}

void LocalMap::AddRange(const grid::Pose2D& pose, double bearing, double range, double reach,
                        double time, double half_width) {
  const bool hit = std::isfinite(range) && range < reach;
  const double length = hit ? std::max(range, 0.0) : reach;
  const double angle = pose.yaw + bearing;
  if (half_width > 0.0) {
    Offsets(static_cast<int>(std::ceil(reach / options_.resolution)) + 1);
    // Up to half a cell short of the end, so the cell the beam ended in is not cleared.
    const double clear = hit ? length - 0.5 * options_.resolution : length;
    const double lo = grid::NormalizeAngle(angle - half_width);
    const double hi = grid::NormalizeAngle(angle + half_width);
    const Eigen::Vector2i from = CellOf(pose.position());
    if (lo <= hi) {
      ClearSector(from, lo, hi, clear, time);
    } else {  // the sector spans the +-pi seam
      ClearSector(from, lo, M_PI + 1e-9, clear, time);
      ClearSector(from, -M_PI - 1e-9, hi, clear, time);
    }
  }
  const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d from = pose.position();
  // Half-cell steps visit every cell the beam crosses closely enough for a map this coarse.
  const double step = options_.resolution * 0.5;
  const Eigen::Vector2i end = CellOf(from + dir * length);
  for (double s = 0.0; s < length; s += step) {
    const Eigen::Vector2i cell = CellOf(from + dir * s);
    if (hit && cell == end) break;
    Set(cell, CellState::kFree, time);
  }
  if (hit) Set(end, CellState::kOccupied, time);
  else Set(end, CellState::kFree, time);
}

bool LocalMap::ClearView(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double stop) const {
  const Eigen::Vector2d way = to - from;
  const double length = way.norm() - stop;
  if (length <= 0.0) return true;
  const Eigen::Vector2d dir = way.normalized();
  // Half-cell steps, as for a beam.
  for (double s = 0.0; s <= length; s += options_.resolution * 0.5) {
    const Eigen::Vector2i cell = CellOf(from + dir * s);
    if (!Inside(cell) || at(cell) != CellState::kFree) return false;
  }
  return true;
}

void LocalMap::MarkFree(const Eigen::Vector2d& centre, double radius, double time) {
  const Eigen::Vector2i lo = CellOf(centre - Eigen::Vector2d::Constant(radius));
  const Eigen::Vector2i hi = CellOf(centre + Eigen::Vector2d::Constant(radius));
  for (int y = lo.y(); y <= hi.y(); ++y)
    for (int x = lo.x(); x <= hi.x(); ++x) Set({x, y}, CellState::kFree, time);
}

void LocalMap::Expire(double time) {
  if (time - swept_ < std::min(options_.expiry_step, options_.expiry)) return;
  swept_ = time;
  const double oldest = time - options_.expiry;
  for (std::size_t i = 0; i < cells_.size(); ++i)
    if (cells_[i] != CellState::kUnknown && seen_[i] < oldest) cells_[i] = CellState::kUnknown;
}

}  // namespace local_navigation
