#include "world_sim/collision.h"

#include <algorithm>
#include <cmath>

namespace world_sim {

bool DiscHitsWalls(const grid::OccupancyMap& map, const Eigen::Vector2d& centre, double radius) {
  // Work in cell coordinates, where cell (i, j) is the unit square at (i, j).
  const Eigen::Vector2d c = map.WorldToCellCoords(centre);
  const double r = radius / map.resolution();
  const int i0 = static_cast<int>(std::floor(c.x() - r)), i1 = static_cast<int>(std::floor(c.x() + r));
  const int j0 = static_cast<int>(std::floor(c.y() - r)), j1 = static_cast<int>(std::floor(c.y() + r));
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      if (!map.Blocks(i, j)) continue;
      const double dx = c.x() - std::clamp(c.x(), static_cast<double>(i), i + 1.0);
      const double dy = c.y() - std::clamp(c.y(), static_cast<double>(j), j + 1.0);
      if (dx * dx + dy * dy < r * r) return true;
    }
  }
  return false;
}

std::optional<double> RayHitsDisc(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                  const Eigen::Vector2d& centre, double radius) {
  const Eigen::Vector2d oc = origin - centre;
  const double b = oc.dot(dir);
  const double c = oc.squaredNorm() - radius * radius;
  const double disc = b * b - c;
  if (disc < 0.0) return std::nullopt;
  const double root = std::sqrt(disc);
  const double t_near = -b - root;
  if (t_near >= 0.0) return t_near;
  if (-b + root >= 0.0) return 0.0;  // the origin is inside the disc
  return std::nullopt;
}

}  // namespace world_sim
