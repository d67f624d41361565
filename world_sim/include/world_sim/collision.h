#pragma once

#include <optional>

#include <Eigen/Core>

#include "grid/occupancy_map.h"

namespace world_sim {

// True when a disc overlaps any blocking cell (occupied, unknown or off the map). Touching a
// wall's face exactly is not an overlap.
bool DiscHitsWalls(const grid::OccupancyMap& map, const Eigen::Vector2d& centre, double radius);

// Distance along the unit ray origin + t * dir (t >= 0) to a disc, or nullopt if it misses.
std::optional<double> RayHitsDisc(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                  const Eigen::Vector2d& centre, double radius);

}  // namespace world_sim
