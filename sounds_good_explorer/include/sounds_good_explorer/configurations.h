#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "grid/occupancy_map.h"
#include "world_sim/world_config.h"

namespace sounds_good_explorer {

// Where a robot's disc can go: free cells at least `radius` from every wall, split into
// connected regions (8-neighbours). A point in region 0 is in a wall or too near one.
class Reachability {
 public:
  Reachability(const grid::OccupancyMap& map, double radius);

  int Region(const Eigen::Vector2d& point) const;
  int largest() const { return largest_; }
  // A point drawn uniformly from the cells of `region` (its cell's centre, jittered in the cell).
  Eigen::Vector2d Sample(int region, std::mt19937& rng) const;

 private:
  const grid::OccupancyMap& map_;
  std::vector<int> labels_;  // per map cell
  std::vector<std::vector<int>> cells_;  // per region, cell indices
  int largest_ = 0;
};

struct ConfigurationOptions {
  int robots = 5;
  std::uint32_t source = 1;
  std::uint32_t sink = 2;
  double margin = 0.05;                 // m of room beyond the robot's radius at every start and marker
  double min_marker_separation = 3.0;   // m between source and sink
};

// A valid starting configuration of the thesis (section 3.4): robots (robot_0 ...) with random
// poses and the source and sink markers, all in free space with room for a robot, nobody
// overlapping, and every marker reachable by every robot. The map file is recorded as given.
world_sim::WorldConfig RandomConfiguration(const grid::OccupancyMap& map,
                                           const std::string& map_file,
                                           const world_sim::RobotModel& model,
                                           const ConfigurationOptions& options, std::mt19937& rng);

// Checks a given configuration for a Sounds Good trial: the source and sink markers exist and
// every robot can reach both. Throws grid::InputError naming `file` and the robot or marker.
void ValidateConfiguration(const std::string& file, const world_sim::WorldConfig& config,
                           const grid::OccupancyMap& map, std::uint32_t source, std::uint32_t sink);

}  // namespace sounds_good_explorer
