#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "grid/pose2d.h"

namespace grid {

enum class Cell : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

// A 2D occupancy bitmap placed in the world. Cell (i, j) is column i, row j; row 0 is at the
// map origin (the bottom of the image), as in nav_msgs/OccupancyGrid. Cell (i, j) covers the
// square [i, i+1) x [j, j+1) in cell coordinates, which are metres / resolution in the frame
// given by `origin` (the pose of the corner of cell (0, 0) in the world).
class OccupancyMap {
 public:
  OccupancyMap() = default;
  // All cells start free. Throws std::invalid_argument on a non-positive size or resolution.
  OccupancyMap(int width, int height, double resolution, const Pose2D& origin = {});

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const Pose2D& origin() const { return origin_; }
  double width_m() const { return width_ * resolution_; }
  double height_m() const { return height_ * resolution_; }

  bool InBounds(int i, int j) const { return i >= 0 && j >= 0 && i < width_ && j < height_; }
  Cell at(int i, int j) const { return cells_[Index(i, j)]; }
  void set(int i, int j, Cell c) { cells_[Index(i, j)] = c; }
  // Whether a cell stops robots, sound and light: occupied, unknown, and everything off the map.
  bool Blocks(int i, int j) const { return !InBounds(i, j) || at(i, j) != Cell::kFree; }

  // World point (m) -> continuous cell coordinates, and back.
  Eigen::Vector2d WorldToCellCoords(const Eigen::Vector2d& world) const;
  Eigen::Vector2d CellCoordsToWorld(const Eigen::Vector2d& cell) const;
  // The cell holding a world point (may be out of bounds), and the world centre of a cell.
  Eigen::Vector2i WorldToCell(const Eigen::Vector2d& world) const;
  Eigen::Vector2d CellCenter(int i, int j) const;

  // Whether a world point lies in a free cell of the map.
  bool IsFreeAt(const Eigen::Vector2d& world) const;

  const std::vector<Cell>& cells() const { return cells_; }

 private:
  std::size_t Index(int i, int j) const { return static_cast<std::size_t>(j) * width_ + i; }

  int width_ = 0;
  int height_ = 0;
  double resolution_ = 1.0;
  Pose2D origin_;
  // cos and sin of the origin's yaw, kept because every ray cast transforms its end points.
  double origin_cos_ = 1.0;
  double origin_sin_ = 0.0;
  std::vector<Cell> cells_;
};

// How many cells of `map` a square at least `side` m across spans (at least 1): the stride of a
// coarse drawing of the map (the rooms in rviz, a level plotted across it).
int CellsAcross(const OccupancyMap& map, double side);

}  // namespace grid
