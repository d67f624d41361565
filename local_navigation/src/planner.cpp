#include "local_navigation/planner.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "grid/option_checks.h"

namespace local_navigation {

using grid::RequireAbove;
using grid::RequireAtLeast;

namespace {

const Eigen::Vector2i kSteps[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

bool Inside(int size, const Eigen::Vector2i& c) {
  return c.x() >= 0 && c.y() >= 0 && c.x() < size && c.y() < size;
}

template <typename T>
Grid<T> MakeGrid(int size, T value) {
  return {size, std::vector<T>(static_cast<std::size_t>(size) * size, value)};
}

}  // namespace

void ValidateOptions(const PlannerOptions& o) {
  RequireAtLeast("planner robot_radius (m)", o.robot_radius, 0.0);
  RequireAbove("planner risk_decay (cells)", o.risk_decay, 0.0);
  if (!(o.risk_scale >= 0.0 && o.risk_scale <= 1000.0))
    throw std::invalid_argument("planner risk_scale must be within 0..1000, got " +
                                std::to_string(o.risk_scale));
  if (!(o.grown_cost >= 1.0 && o.grown_cost <= 100000.0))
    throw std::invalid_argument("planner grown_cost must be within 1..100000, got " +
                                std::to_string(o.grown_cost));
}

Grid<std::uint8_t> GrowObstacles(const LocalMap& map, int radius_cells) {
  const int n = map.size();
  Grid<std::uint8_t> grown = MakeGrid<std::uint8_t>(n, 0);
  for (std::size_t i = 0; i < grown.values.size(); ++i)
    grown.values[i] = map.cells()[i] == CellState::kOccupied ? 255 : 0;
  if (radius_cells <= 0) return grown;
  cv::Mat occupied(n, n, CV_8UC1, grown.values.data());
  // A Euclidean disc of the radius, so a robot's clearance is the same in every direction.
  const int k = 2 * radius_cells + 1;
  cv::Mat disc = cv::Mat::zeros(k, k, CV_8UC1);
  for (int y = -radius_cells; y <= radius_cells; ++y)
    for (int x = -radius_cells; x <= radius_cells; ++x)
      if (x * x + y * y <= radius_cells * radius_cells)
        disc.at<std::uint8_t>(y + radius_cells, x + radius_cells) = 1;
  cv::Mat dilated;
  cv::dilate(occupied, dilated, disc, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  std::copy(dilated.datastart, dilated.dataend, grown.values.begin());
  return grown;
}

Grid<int> ManhattanDistance(const Grid<std::uint8_t>& obstacles) {
  const int n = obstacles.size;
  Grid<int> distance = MakeGrid<int>(n, 2 * n);
  if (std::none_of(obstacles.values.begin(), obstacles.values.end(),
                   [](std::uint8_t v) { return v != 0; }))
    return distance;
  // OpenCV measures the distance to the nearest zero pixel; with the L1 metric and a 3x3 mask
  // its two-pass transform is exact.
  cv::Mat free(n, n, CV_8UC1);
  for (std::size_t i = 0; i < obstacles.values.size(); ++i)
    free.data[i] = obstacles.values[i] ? 0 : 255;
  // Whole numbers under the L1 metric: 8-bit output (saturating at 255) needs no rounding.
  cv::Mat dist;
  cv::distanceTransform(free, dist, cv::DIST_L1, 3, CV_8U);
  std::copy(dist.datastart, dist.dataend, distance.values.begin());
  return distance;
}

Grid<std::uint32_t> StepCosts(const LocalMap& map, const Grid<std::uint8_t>& grown,
                              const Grid<int>& distance, const PlannerOptions& options) {
  const int n = map.size();
  Grid<std::uint32_t> costs = MakeGrid<std::uint32_t>(n, 0);
  // The risk depends only on the distance: tabulate it once.
  std::vector<std::uint32_t> by_distance(2 * n + 1);
  for (int d = 0; d <= 2 * n; ++d)
    by_distance[d] = 10 + static_cast<std::uint32_t>(
                              std::lround(10.0 * options.risk_scale * std::exp(-d / options.risk_decay)));
  const auto grown_cost = static_cast<std::uint32_t>(std::lround(10.0 * options.grown_cost));
  for (std::size_t i = 0; i < costs.values.size(); ++i) {
    if (map.cells()[i] == CellState::kOccupied) costs.values[i] = kUnreachable;
    else if (grown.values[i]) costs.values[i] = grown_cost;
    else costs.values[i] = by_distance[std::min(distance.values[i], 2 * n)];
  }
  return costs;
}

Grid<std::uint32_t> Wavefront(const Grid<std::uint32_t>& costs, const Eigen::Vector2i& goal,
                              const std::optional<Eigen::Vector2i>& stop_at) {
  const int n = costs.size;
  Grid<std::uint32_t> potential = MakeGrid<std::uint32_t>(n, kUnreachable);
  // The goal's own cost is never paid, so a goal in an occupied cell (a marker drawn next to a
  // wall) is still reached from its free neighbours.
  if (!Inside(n, goal)) return potential;
  std::uint32_t max_cost = 1;
  for (std::uint32_t c : costs.values)
    if (c != kUnreachable) max_cost = std::max(max_cost, c);
  const int stop = stop_at && Inside(n, *stop_at) ? stop_at->y() * n + stop_at->x() : -1;
  // Dial's bucket queue: every step costs at most max_cost, so max_cost + 1 circular buckets
  // hold all cells waiting, and each cell is settled once: O(cells + largest potential). The
  // buckets are kept per thread between calls and emptied at the start of each, so planning
  // does not allocate.
  thread_local std::vector<std::vector<int>> buckets;
  for (auto& bucket : buckets) bucket.clear();
  if (buckets.size() != max_cost + 1) buckets.resize(max_cost + 1);
  std::vector<std::uint32_t>& p = potential.values;
  const std::vector<std::uint32_t>& cost = costs.values;
  const int start = goal.y() * n + goal.x();
  p[start] = 0;
  buckets[0].push_back(start);
  std::size_t waiting = 1;
  for (std::uint32_t d = 0; waiting > 0; ++d) {
    std::vector<int>& bucket = buckets[d % buckets.size()];
    while (!bucket.empty()) {
      const int index = bucket.back();
      bucket.pop_back();
      --waiting;
      if (p[index] != d) continue;  // settled earlier at a lower value
      if (index == stop) return potential;
      const int x = index % n, y = index / n;
      const int neighbours[4] = {x + 1 < n ? index + 1 : -1, x > 0 ? index - 1 : -1,
                                 y + 1 < n ? index + n : -1, y > 0 ? index - n : -1};
      for (int next : neighbours) {
        if (next < 0 || cost[next] == kUnreachable) continue;
        // 64-bit sum: a huge map of costly cells must not wrap round to a small potential.
        const std::uint64_t sum = static_cast<std::uint64_t>(d) + cost[next];
        if (sum >= p[next]) continue;
        const auto value = static_cast<std::uint32_t>(sum);
        p[next] = value;
        buckets[value % buckets.size()].push_back(next);
        ++waiting;
      }
    }
  }
  return potential;
}

std::vector<Eigen::Vector2i> SteepestDescent(const Grid<std::uint32_t>& potential,
                                             const Eigen::Vector2i& start) {
  const int n = potential.size;
  std::vector<Eigen::Vector2i> path;
  if (!Inside(n, start) || potential.at(start) == kUnreachable) return path;
  Eigen::Vector2i cell = start;
  path.push_back(cell);
  // Each move lowers the potential, so the walk ends at the goal within the cell count.
  while (potential.at(cell) != 0) {
    Eigen::Vector2i best = cell;
    for (const Eigen::Vector2i& step : kSteps) {
      const Eigen::Vector2i next = cell + step;
      if (Inside(n, next) && potential.at(next) < potential.at(best)) best = next;
    }
    if (best == cell) return {};  // a local minimum cannot happen in a wavefront; be safe
    cell = best;
    path.push_back(cell);
  }
  return path;
}

Grid<std::uint32_t> PlanningCosts(const LocalMap& map, const PlannerOptions& options) {
  const int radius = static_cast<int>(std::ceil(options.robot_radius / map.resolution() - 1e-9));
  const Grid<std::uint8_t> grown = GrowObstacles(map, radius);
  return StepCosts(map, grown, ManhattanDistance(grown), options);
}

Plan MakePlan(const LocalMap& map, const Eigen::Vector2i& start, const Eigen::Vector2i& goal,
              const PlannerOptions& options) {
  Plan plan;
  plan.potential = Wavefront(PlanningCosts(map, options), goal, start);
  plan.cells = SteepestDescent(plan.potential, start);
  return plan;
}

}  // namespace local_navigation
