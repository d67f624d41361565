#pragma once

#include <optional>

#include <Eigen/Core>

#include "grid/occupancy_map.h"

namespace grid {

// Exact segment tests against the blocking cells of a map (occupied, unknown, off the map).
//
// A segment is blocked where it enters the interior of a blocking cell, runs along the edge
// between two blocking cells, or passes through a grid vertex where two diagonally opposite
// cells block (a diagonal wall drawn with cells that touch only at corners is still a wall).
// Grazing a wall, touching its corner or running along its face, is not blocked: that is how
// sound bends around a corner. Coordinates that are within 1e-9 cells of a grid line count as
// on it, so corner grazes computed from world coordinates stay exact.

// Fraction t in [0, 1] of the way from `from` to `to` (world metres) where the segment is first
// blocked, or nullopt when the whole segment is clear.
std::optional<double> FirstBlocked(const OccupancyMap& map, const Eigen::Vector2d& from,
                                   const Eigen::Vector2d& to);

// The same in continuous cell coordinates (see OccupancyMap::WorldToCellCoords), for callers
// that work on the grid directly.
std::optional<double> FirstBlockedInCells(const OccupancyMap& map, const Eigen::Vector2d& from,
                                          const Eigen::Vector2d& to);

// True when nothing blocks the segment between the two world points.
bool LineOfSight(const OccupancyMap& map, const Eigen::Vector2d& from, const Eigen::Vector2d& to);

// Distance (m) from `origin` along the world-frame heading `angle` to the first blocking cell,
// or nullopt when nothing blocks within `max_range`.
std::optional<double> CastRay(const OccupancyMap& map, const Eigen::Vector2d& origin,
                              double angle, double max_range);
// The same along a unit direction vector, for callers that rotate a ring of beams themselves.
std::optional<double> CastRay(const OccupancyMap& map, const Eigen::Vector2d& origin,
                              const Eigen::Vector2d& direction, double max_range);

}  // namespace grid
