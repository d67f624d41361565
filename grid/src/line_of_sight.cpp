#include "grid/line_of_sight.h"

#include <cmath>
#include <limits>

namespace grid {
namespace {

constexpr double kEps = 1e-9;  // cells
constexpr double kInf = std::numeric_limits<double>::infinity();

bool NearInteger(double v) { return std::abs(v - std::round(v)) <= kEps; }

// First cell index a walk starting at coordinate `a` in direction `d` enters.
int StartIndex(double a, double d) {
  if (d > 0.0) return static_cast<int>(std::floor(a + kEps));
  if (d < 0.0) return static_cast<int>(std::ceil(a - kEps)) - 1;
  return static_cast<int>(std::floor(a));
}

// A segment lying on the grid line v = k, running from u = a to u = b (cell coordinates).
// `blocks(u, v)` tells whether cell (u, v) blocks, in the segment's own axis order.
template <typename BlocksFn>
std::optional<double> AlongGridLine(double a, double b, int k, BlocksFn blocks) {
  const double d = b - a;
  const int s = d > 0.0 ? 1 : -1;
  int iu = StartIndex(a, d);
  double t = 0.0;
  while (true) {
    if (blocks(iu, k - 1) && blocks(iu, k)) return t;  // inside a wall, not on its face
    const int boundary = s > 0 ? iu + 1 : iu;
    const double t_next = (boundary - a) / d;
    if (t_next * std::abs(d) >= std::abs(d) - kEps) return std::nullopt;
    const int next = iu + s;
    if ((blocks(iu, k - 1) && blocks(next, k)) || (blocks(iu, k) && blocks(next, k - 1))) {
      return t_next;  // a diagonal wall crosses the line at this vertex
    }
    iu = next;
    t = t_next;
  }
}

// Amanatides-Woo cell walk with exact handling of grid vertices, for segments that do not lie
// on a grid line. `blocks(i, j)` tells whether cell (i, j) blocks.
template <typename BlocksFn>
std::optional<double> CellWalk(const Eigen::Vector2d& a, const Eigen::Vector2d& b, BlocksFn blocks) {
  const Eigen::Vector2d d = b - a;
  const double len = d.norm();
  const int sx = d.x() > 0.0 ? 1 : (d.x() < 0.0 ? -1 : 0);
  const int sy = d.y() > 0.0 ? 1 : (d.y() < 0.0 ? -1 : 0);
  int ix = StartIndex(a.x(), d.x());
  int iy = StartIndex(a.y(), d.y());
  const double delta_x = sx != 0 ? 1.0 / std::abs(d.x()) : kInf;
  const double delta_y = sy != 0 ? 1.0 / std::abs(d.y()) : kInf;
  double t_max_x = sx > 0 ? (ix + 1 - a.x()) / d.x() : (sx < 0 ? (ix - a.x()) / d.x() : kInf);
  double t_max_y = sy > 0 ? (iy + 1 - a.y()) / d.y() : (sy < 0 ? (iy - a.y()) / d.y() : kInf);
  // Tolerances in units of t: crossings within kEps cells of the end, or of each other.
  const double t_end = 1.0 - kEps / len, t_tie = kEps / len;
  double t = 0.0;
  while (true) {
    if (blocks(ix, iy)) return t;
    const double t_next = std::min(t_max_x, t_max_y);
    if (t_next >= t_end) return std::nullopt;
    if (std::abs(t_max_x - t_max_y) <= t_tie) {
      // Through a vertex: the two side cells are only touched, but if both block, the
      // segment squeezes through a diagonal wall.
      if (blocks(ix + sx, iy) && blocks(ix, iy + sy)) return t_next;
      ix += sx;
      iy += sy;
      t_max_x += delta_x;
      t_max_y += delta_y;
    } else if (t_max_x < t_max_y) {
      ix += sx;
      t_max_x += delta_x;
    } else {
      iy += sy;
      t_max_y += delta_y;
    }
    t = t_next;
  }
}

}  // namespace

std::optional<double> FirstBlockedInCells(const OccupancyMap& map, const Eigen::Vector2d& a,
                                          const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  if (d.norm() <= kEps) {
    return map.Blocks(static_cast<int>(std::floor(a.x())), static_cast<int>(std::floor(a.y())))
               ? std::optional<double>(0.0)
               : std::nullopt;
  }
  if (std::abs(d.y()) <= kEps && NearInteger(a.y())) {
    return AlongGridLine(a.x(), b.x(), static_cast<int>(std::lround(a.y())),
                         [&](int u, int v) { return map.Blocks(u, v); });
  }
  if (std::abs(d.x()) <= kEps && NearInteger(a.x())) {
    return AlongGridLine(a.y(), b.y(), static_cast<int>(std::lround(a.x())),
                         [&](int u, int v) { return map.Blocks(v, u); });
  }
  // Every cell the walk can look at lies within one cell of the segment's bounding box; when
  // that box is on the map, skip the per-cell bounds checks (the hot path of every ray cast).
  const double lo_x = std::min(a.x(), b.x()) - 1.0, hi_x = std::max(a.x(), b.x()) + 1.0;
  const double lo_y = std::min(a.y(), b.y()) - 1.0, hi_y = std::max(a.y(), b.y()) + 1.0;
  if (lo_x >= 0.0 && lo_y >= 0.0 && hi_x < map.width() && hi_y < map.height()) {
    const Cell* cells = map.cells().data();
    const int w = map.width();
    return CellWalk(a, b, [cells, w](int i, int j) { return cells[j * w + i] != Cell::kFree; });
  }
  return CellWalk(a, b, [&map](int i, int j) { return map.Blocks(i, j); });
}

std::optional<double> FirstBlocked(const OccupancyMap& map, const Eigen::Vector2d& from,
                                   const Eigen::Vector2d& to) {
  return FirstBlockedInCells(map, map.WorldToCellCoords(from), map.WorldToCellCoords(to));
}

bool LineOfSight(const OccupancyMap& map, const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  return !FirstBlocked(map, from, to).has_value();
}

std::optional<double> CastRay(const OccupancyMap& map, const Eigen::Vector2d& origin,
                              double angle, double max_range) {
  return CastRay(map, origin, Eigen::Vector2d(std::cos(angle), std::sin(angle)), max_range);
}

std::optional<double> CastRay(const OccupancyMap& map, const Eigen::Vector2d& origin,
                              const Eigen::Vector2d& direction, double max_range) {
  const Eigen::Vector2d end = origin + max_range * direction;
  const std::optional<double> t = FirstBlocked(map, origin, end);
  if (!t) return std::nullopt;
  return *t * max_range;
}

}  // namespace grid
