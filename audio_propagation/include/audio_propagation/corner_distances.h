#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/visibility_graph.h"

namespace audio_propagation {

// Shortest distances between every pair of corners of a visibility graph (one Dijkstra run
// with a binary heap from each corner, bounded by `reach_cells`), with predecessors to rebuild
// the paths. Built once per map so that a simulation step only joins each source and listener
// through the corners they see. Memory: 8 bytes per pair of corners.
class CornerDistances {
 public:
  CornerDistances(const VisibilityGraph& graph, double reach_cells, int threads = 1);

  // Cells of path from corner a to corner b; +inf when b is out of reach.
  float distance(std::size_t a, std::size_t b) const { return dist_[a * n_ + b]; }
  // Appends the corners of the path from a to b, a first and b last.
  void AppendPath(const VisibilityGraph& graph, std::size_t a, std::size_t b,
                  std::vector<Eigen::Vector2d>& out) const;

 private:
  std::size_t n_;
  std::vector<float> dist_;
  std::vector<std::int32_t> prev_;  // prev_[a * n + b]: the corner before b on the path from a
};

}  // namespace audio_propagation
