#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "local_navigation/local_map.h"

namespace local_navigation {

struct PlannerOptions {
  double robot_radius = 0.075;  // m: obstacles are grown by this much
  // Risk of a cell at Manhattan distance d (cells) from the nearest grown obstacle:
  // risk_scale * exp(-d / risk_decay), in cell steps (a step itself costs 1).
  double risk_scale = 8.0;
  double risk_decay = 1.5;
  // Cells inside grown obstacles cost this many steps: passable, so a robot that finds itself
  // there (odometry drift, a robot that came close) can still leave, but never chosen freely.
  double grown_cost = 200.0;
};

void ValidateOptions(const PlannerOptions& options);

// A row-major grid of the local map's size.
template <typename T>
struct Grid {
  int size = 0;
  std::vector<T> values;
  T& at(const Eigen::Vector2i& c) { return values[static_cast<std::size_t>(c.y()) * size + c.x()]; }
  const T& at(const Eigen::Vector2i& c) const {
    return values[static_cast<std::size_t>(c.y()) * size + c.x()];
  }
};

constexpr std::uint32_t kUnreachable = std::numeric_limits<std::uint32_t>::max();

// The planning steps of thesis section 3.3.4 (after Batavia), each a pure function:
// occupied cells grown by `radius_cells` (Euclidean disc), unknown cells taken as free.
Grid<std::uint8_t> GrowObstacles(const LocalMap& map, int radius_cells);
// City-block distance (cells) from each cell to the nearest obstacle cell (0 on obstacles);
// `size` * 2 when the grid holds no obstacle.
Grid<int> ManhattanDistance(const Grid<std::uint8_t>& obstacles);
// Integer cost of entering each cell, in tenths of a step: 10 for a step plus the exponential
// risk of its distance; grown cells `grown_cost`; cells occupied in `map` kUnreachable.
Grid<std::uint32_t> StepCosts(const LocalMap& map, const Grid<std::uint8_t>& grown,
                              const Grid<int>& distance, const PlannerOptions& options);
// Wavefront potential: least total cost from `goal` to each cell over 4-connected steps
// (the goal itself 0, even in an occupied cell; kUnreachable where no path). A bucket queue on
// the integer costs keeps it O(cells + largest potential), as the thesis's FIFO flood fill is
// linear in the cells. With `stop_at`, the fill stops once
// that cell is settled: cells costlier than it may keep unfinished (too high) values, which
// steepest descent from it never looks at.
Grid<std::uint32_t> Wavefront(const Grid<std::uint32_t>& costs, const Eigen::Vector2i& goal,
                              const std::optional<Eigen::Vector2i>& stop_at = std::nullopt);
// From `start`, always into the lowest-valued 4-neighbour until the goal (potential 0).
// Empty when `start` cannot reach the goal.
std::vector<Eigen::Vector2i> SteepestDescent(const Grid<std::uint32_t>& potential,
                                             const Eigen::Vector2i& start);

struct Plan {
  std::vector<Eigen::Vector2i> cells;  // start to goal; empty when the goal cannot be reached
  Grid<std::uint32_t> potential;
};

// The cost of entering each cell of `map`: obstacles grown by the robot's radius, then StepCosts.
Grid<std::uint32_t> PlanningCosts(const LocalMap& map, const PlannerOptions& options);

// The whole chain, O(cells) per plan.
Plan MakePlan(const LocalMap& map, const Eigen::Vector2i& start, const Eigen::Vector2i& goal,
              const PlannerOptions& options);

}  // namespace local_navigation
