#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/diffraction_points.h"
#include "grid/occupancy_map.h"

namespace audio_propagation {

// Mutual visibility among the places where sound bends, built once per map. Positions and
// lengths are in cell coordinates (multiply lengths by the resolution for metres).
// Each pair is tested once with exact line of sight, and only when the line between them is
// tangent to the wall at both corners; pairs farther apart than `max_range_cells` (0 = no
// limit) are not tested. Edges are kept in compressed rows for fast Dijkstra runs.
class VisibilityGraph {
 public:
  struct Edge {
    std::int32_t to;
    float length;
  };

  // `threads` > 1 splits the pair tests over that many threads.
  VisibilityGraph(const grid::OccupancyMap& map, std::vector<Corner> corners,
                  double max_range_cells, int threads = 1);

  std::size_t size() const { return positions_.size(); }
  const Corner& corner(std::size_t node) const { return corners_[node]; }
  std::size_t edge_count() const { return edges_.size() / 2; }  // undirected
  const Eigen::Vector2d& position(std::size_t node) const { return positions_[node]; }
  const std::vector<Eigen::Vector2d>& positions() const { return positions_; }
  const Edge* edges_begin(std::size_t node) const { return edges_.data() + offsets_[node]; }
  const Edge* edges_end(std::size_t node) const { return edges_.data() + offsets_[node + 1]; }

 private:
  std::vector<Corner> corners_;
  std::vector<Eigen::Vector2d> positions_;
  std::vector<std::size_t> offsets_;
  std::vector<Edge> edges_;
};

}  // namespace audio_propagation
