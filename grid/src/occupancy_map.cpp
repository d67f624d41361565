#include "grid/occupancy_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace grid {

OccupancyMap::OccupancyMap(int width, int height, double resolution, const Pose2D& origin)
    : width_(width), height_(height), resolution_(resolution), origin_(origin) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("OccupancyMap: size must be positive, got " +
                                std::to_string(width) + " x " + std::to_string(height));
  }
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("OccupancyMap: resolution must be positive, got " +
                                std::to_string(resolution));
  }
  origin_cos_ = std::cos(origin.yaw);
  origin_sin_ = std::sin(origin.yaw);
  cells_.assign(static_cast<std::size_t>(width) * height, Cell::kFree);
}

Eigen::Vector2d OccupancyMap::WorldToCellCoords(const Eigen::Vector2d& world) const {
  const double dx = world.x() - origin_.x, dy = world.y() - origin_.y;
  return Eigen::Vector2d(origin_cos_ * dx + origin_sin_ * dy, -origin_sin_ * dx + origin_cos_ * dy) /
         resolution_;
}

Eigen::Vector2d OccupancyMap::CellCoordsToWorld(const Eigen::Vector2d& cell) const {
  const Eigen::Vector2d p = cell * resolution_;
  return {origin_.x + origin_cos_ * p.x() - origin_sin_ * p.y(),
          origin_.y + origin_sin_ * p.x() + origin_cos_ * p.y()};
}

namespace {

// A cell index for a cell coordinate. Points beyond int's reach (a pose typed with too many
// digits, an infinity) and NaN come out far off any map, on their side of it (NaN below), and
// still far enough from int's limits that a neighbour's index does not overflow.
int CellIndex(double c) {
  constexpr double kFar = 1 << 30;
  if (!(c > -kFar)) return -(1 << 30);
  if (c >= kFar) return 1 << 30;
  return static_cast<int>(std::floor(c));
}

}  // namespace

Eigen::Vector2i OccupancyMap::WorldToCell(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d c = WorldToCellCoords(world);
  return {CellIndex(c.x()), CellIndex(c.y())};
}

Eigen::Vector2d OccupancyMap::CellCenter(int i, int j) const {
  return CellCoordsToWorld({i + 0.5, j + 0.5});
}

bool OccupancyMap::IsFreeAt(const Eigen::Vector2d& world) const {
  const Eigen::Vector2i c = WorldToCell(world);
  return !Blocks(c.x(), c.y());
}

int CellsAcross(const OccupancyMap& map, double side) {
  // Less a hair, so that a side that is a whole number of cells is not rounded up by one.
  return std::max(1, static_cast<int>(std::ceil(side / map.resolution() - 1e-9)));
}

}  // namespace grid
