#pragma once

#include <random>
#include <vector>

#include <Eigen/Core>

#include "grid/occupancy_map.h"

namespace grid {

// Where a robot's disc can go: free cells at least `radius` from every wall, split into
// connected regions (8-neighbours). A point in region 0 is in a wall or too near one.
class Reachability {
 public:
  Reachability(const OccupancyMap& map, double radius);

  int Region(const Eigen::Vector2d& point) const;
  int largest() const { return largest_; }
  // A point drawn uniformly from the cells of `region` (its cell's centre, jittered in the cell).
  Eigen::Vector2d Sample(int region, std::mt19937& rng) const;

 private:
  const OccupancyMap& map_;
  std::vector<int> labels_;  // per map cell
  std::vector<std::vector<int>> cells_;  // per region, cell indices
  int largest_ = 0;
};

}  // namespace grid
