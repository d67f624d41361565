#include "audio_propagation/corner_distances.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <thread>
#include <utility>

namespace audio_propagation {

CornerDistances::CornerDistances(const VisibilityGraph& graph, double reach_cells, int threads)
    : n_(graph.size()),
      dist_(n_ * n_, std::numeric_limits<float>::infinity()),
      prev_(n_ * n_, -1) {
  auto row = [&](std::size_t source) {
    float* dist = dist_.data() + source * n_;
    std::int32_t* prev = prev_.data() + source * n_;
    using Entry = std::pair<double, std::int32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
    std::vector<double> best(n_, std::numeric_limits<double>::infinity());
    best[source] = 0.0;
    heap.emplace(0.0, static_cast<std::int32_t>(source));
    while (!heap.empty()) {
      const auto [d, u] = heap.top();
      heap.pop();
      if (d > best[u]) continue;
      dist[u] = static_cast<float>(d);
      for (const VisibilityGraph::Edge* e = graph.edges_begin(u); e != graph.edges_end(u); ++e) {
        const double nd = d + e->length;
        if (nd < best[e->to] && nd <= reach_cells) {
          best[e->to] = nd;
          prev[e->to] = u;
          heap.emplace(nd, e->to);
        }
      }
    }
  };
  threads = std::max(1, threads);
  auto work = [&](int t) {
    for (std::size_t s = t; s < n_; s += threads) row(s);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& th : pool) th.join();
}

void CornerDistances::AppendPath(const VisibilityGraph& graph, std::size_t a, std::size_t b,
                                 std::vector<Eigen::Vector2d>& out) const {
  const std::size_t start = out.size();
  for (std::int32_t k = static_cast<std::int32_t>(b); k >= 0; k = prev_[a * n_ + k]) {
    out.push_back(graph.position(k));
    if (static_cast<std::size_t>(k) == a) break;
  }
  std::reverse(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
}

}  // namespace audio_propagation
