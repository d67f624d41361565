#include "audio_propagation/visibility_graph.h"

#include <algorithm>
#include <thread>
#include <utility>

#include "grid/line_of_sight.h"

namespace audio_propagation {

VisibilityGraph::VisibilityGraph(const grid::OccupancyMap& map,
                                 std::vector<Corner> corners, double max_range_cells,
                                 int threads)
    : corners_(std::move(corners)) {
  for (const Corner& c : corners_) positions_.push_back(c.position);
  const std::size_t n = positions_.size();
  const double range2 = max_range_cells > 0.0 ? max_range_cells * max_range_cells : -1.0;

  // Each worker tests the pairs (i, j > i) of every threads-th row i, so that the work of the
  // long early rows and the short late rows is shared evenly.
  threads = std::max(1, threads);
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> found(threads);
  auto work = [&](int t) {
    for (std::size_t i = t; i < n; i += threads) {
      for (std::size_t j = i + 1; j < n; ++j) {
        const Eigen::Vector2d d = positions_[j] - positions_[i];
        if (range2 > 0.0 && d.squaredNorm() > range2) continue;
        if (!corners_[i].Tangent(d) || !corners_[j].Tangent(d)) continue;
        if (!grid::FirstBlockedInCells(map, positions_[i], positions_[j])) {
          found[t].emplace_back(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j));
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& th : pool) th.join();

  std::vector<std::size_t> degree(n + 1, 0);
  for (const auto& list : found) {
    for (const auto& [a, b] : list) {
      ++degree[a];
      ++degree[b];
    }
  }
  offsets_.assign(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) offsets_[k + 1] = offsets_[k] + degree[k];
  edges_.resize(offsets_[n]);
  std::vector<std::size_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (const auto& list : found) {
    for (const auto& [a, b] : list) {
      const float len = static_cast<float>((positions_[a] - positions_[b]).norm());
      edges_[fill[a]++] = {b, len};
      edges_[fill[b]++] = {a, len};
    }
  }
}

}  // namespace audio_propagation
