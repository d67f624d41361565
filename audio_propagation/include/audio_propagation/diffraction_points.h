#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "grid/occupancy_map.h"

namespace audio_propagation {

// Which free cells may bend a sound path (thesis section 2.3).
enum class DiffractionRule {
  // The thesis's rule: a free cell is a diffraction point unless its 3x3 neighbourhood is one
  // whose centre cannot bend a path: empty, a straight wall, an inside corner, a one-cell
  // corridor or a dead end (in any rotation or reflection).
  kMasks,
  // Only free cells diagonal to a convex wall corner (the diagonal neighbour blocks, the two
  // cells between them are free). A subset of kMasks giving the same shortest paths.
  kConvexCorners,
};

std::optional<DiffractionRule> ParseDiffractionRule(const std::string& name);  // masks | convex_corners
const char* DiffractionRuleName(DiffractionRule rule);

// The 3x3 neighbourhood of cell (i, j) as a 9-bit code: bit (dy + 1) * 3 + (dx + 1) is set when
// cell (i + dx, j + dy) blocks (occupied, unknown or off the map). Bit 4 is the centre.
std::uint16_t NeighbourhoodCode(const grid::OccupancyMap& map, int i, int j);

// Whether a neighbourhood code makes its centre a diffraction point under `rule`.
bool IsDiffractionCode(std::uint16_t code, DiffractionRule rule);

// Every diffraction point of the map, in row-major cell order.
std::vector<Eigen::Vector2i> FindDiffractionPoints(const grid::OccupancyMap& map, DiffractionRule rule);

// Where sound bends at the given diffraction points: the convex wall corners they touch, as grid
// vertices in cell coordinates (a vertex is a convex corner when exactly one of the four cells
// around it blocks). Each vertex appears once, however many points touch it. Bending at the
// corner itself, rather than at the centre of the cell beside it, makes path lengths exact:
// shortest paths around the blocked cells bend only at such corners.
struct Corner {
  Eigen::Vector2d position;  // the grid vertex, in cell coordinates
  int qx = 0, qy = 0;        // the blocking cell lies towards (qx, qy), each +1 or -1

  // Whether a straight line along `d` through this corner only touches the wall here (is
  // tangent to it). Shortest paths bend only at corners their segments are tangent to, so
  // other lines need no line-of-sight test: the reduced visibility graph.
  bool Tangent(const Eigen::Vector2d& d) const { return d.x() * d.y() * qx * qy <= 0.0; }
};
std::vector<Corner> CornerVertices(const grid::OccupancyMap& map,
                                   const std::vector<Eigen::Vector2i>& points);

}  // namespace audio_propagation
