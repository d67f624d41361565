#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "grid/pose2d.h"

namespace local_navigation {

enum class CellState : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

struct LocalMapOptions {
  int size = 41;             // cells on a side (odd, so one cell is the centre): 6.15 m
  double resolution = 0.15;  // m per cell: the thesis's robot size
  double expiry = 20.0;      // s after which a cell not seen again reverts to unknown
  double expiry_step = 1.0;  // s between sweeps for expired cells (at most `expiry`)
};

// Throws std::invalid_argument naming the field when an option is impossible.
void ValidateOptions(const LocalMapOptions& options);

// The thesis's "local map" (section 3.3.2): a fixed-size occupancy grid in the odometry frame,
// kept centred on the robot by shifting whole cells (cells that fall off the edge are lost),
// filled from range readings, with every cell reverting to unknown `expiry` s after it was
// last seen (other robots move; odometry slips). Cells are aligned to a grid fixed in the odom
// frame, so shifting never blurs them. Cell (0, 0) is the lower-left corner.
class LocalMap {
 public:
  explicit LocalMap(const LocalMapOptions& options);

  // Moves the map so that `position` (odom frame) lies in the centre cell.
  void Recentre(const Eigen::Vector2d& position);
  // Marks what one ranger saw from `pose`: free along the beam up to `range` (or `reach` when
  // nothing was in reach: range +inf, NaN or beyond reach), and occupied where it ended on
  // something. `bearing` is the ranger's angle in the robot frame. With `half_width` > 0 the
  // reading also clears the sector bearing +- half_width up to that range (cells are taken
  // from the robot's cell centre), as a sonar-style ranger model does: a ring of rangers then
  // sees all round, not only along its few beams.
  void AddRange(const grid::Pose2D& pose, double bearing, double range, double reach, double time,
                double half_width = 0.0);
  // Whether the map shows open space all the way from `from` to `stop` m short of `to`: every
  // cell on the way known and free (unknown cells may hide a wall, and off the map nothing is
  // known). Says whether a camera at `from` would see something at `to`.
  bool ClearView(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double stop) const;
  // Marks a disc free (the robot's own body).
  void MarkFree(const Eigen::Vector2d& centre, double radius, double time);
  // Reverts cells last seen more than `expiry` s before `time` to unknown. The sweep over the
  // cells runs at most once per `expiry_step` s: a cell may outlive its expiry by that much.
  void Expire(double time);

  int size() const { return options_.size; }
  double resolution() const { return options_.resolution; }
  bool Inside(const Eigen::Vector2i& cell) const {
    return cell.x() >= 0 && cell.y() >= 0 && cell.x() < options_.size && cell.y() < options_.size;
  }
  CellState at(const Eigen::Vector2i& cell) const { return cells_[Index(cell)]; }
  void Set(const Eigen::Vector2i& cell, CellState state, double time);
  // Odom-frame point to the cell containing it (may be outside), and a cell's centre.
  Eigen::Vector2i CellOf(const Eigen::Vector2d& point) const;
  Eigen::Vector2d CentreOf(const Eigen::Vector2i& cell) const;
  Eigen::Vector2i centre_cell() const { return {options_.size / 2, options_.size / 2}; }
  // Odom-frame cell index of cell (0, 0): the map covers [origin, origin + size) in odom cells.
  const Eigen::Vector2i& origin() const { return origin_; }
  const std::vector<CellState>& cells() const { return cells_; }  // row-major, y rows

 private:
  // A cell within reach of the robot's cell: offset, direction and distance from its centre.
  struct Offset {
    double angle;  // rad, (-pi, pi]
    double distance;  // m
    Eigen::Vector2i cell;
  };
  // The offsets within `radius` cells, sorted by angle (built once per radius).
  const std::vector<Offset>& Offsets(int radius);
  void ClearSector(const Eigen::Vector2i& from, double lo, double hi, double length, double time);

  std::size_t Index(const Eigen::Vector2i& cell) const {
    return static_cast<std::size_t>(cell.y()) * options_.size + cell.x();
  }

  LocalMapOptions options_;
  Eigen::Vector2i origin_{0, 0};
  bool placed_ = false;
  std::vector<CellState> cells_;
  // s, when each cell was last marked (double: ROS wall-clock stamps are ~1.7e9 s)
  std::vector<double> seen_;
  double swept_ = -1e9;      // s, last sweep for expired cells
  int offsets_radius_ = -1;
  std::vector<Offset> offsets_;
};

}  // namespace local_navigation
