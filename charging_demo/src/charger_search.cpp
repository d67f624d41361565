#include "charging_demo/charger_search.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "grid/option_checks.h"
#include "grid/pose2d.h"

namespace charging_demo {

void ValidateOptions(const SearchOptions& o) {
  grid::RequireAbove("search cell (m)", o.cell, 0.0);
  grid::RequireAbove("search goal_distance (m)", o.goal_distance, 0.0);
  grid::RequireAbove("search hold (s)", o.hold, 0.0);
  grid::RequireAtLeast("search unreachable_penalty (s)", o.unreachable_penalty, 0.0);
  if (o.directions < 1)
    throw std::invalid_argument("search directions must be at least 1, got " + std::to_string(o.directions));
}

ChargerSearch::ChargerSearch(const SearchOptions& options) : options_((ValidateOptions(options), options)) {}

std::pair<int, int> ChargerSearch::CellOf(const Eigen::Vector2d& p) const {
  return {static_cast<int>(std::floor(p.x() / options_.cell)), static_cast<int>(std::floor(p.y() / options_.cell))};
}

void ChargerSearch::Visit(const Eigen::Vector2d& position, double dt) { visits_[CellOf(position)] += dt; }

void ChargerSearch::MarkUnreachable(const Eigen::Vector2d& goal) { Visit(goal, options_.unreachable_penalty); }

double ChargerSearch::Visits(const Eigen::Vector2d& position) const {
  const auto it = visits_.find(CellOf(position));
  return it == visits_.end() ? 0.0 : it->second;
}

double ChargerSearch::Neighbourhood(const Eigen::Vector2d& position) const {
  const auto [cx, cy] = CellOf(position);
  double sum = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const auto it = visits_.find({cx + dx, cy + dy});
      if (it != visits_.end()) sum += it->second;
    }
  return sum;
}

Eigen::Vector2d ChargerSearch::ChooseGoal(const Eigen::Vector2d& position,
                                          const local_navigation::LocalMap& map, std::mt19937& rng,
                                          std::optional<double> excluded_direction) const {
  std::vector<Eigen::Vector2d> best;
  double best_score = std::numeric_limits<double>::infinity();
  const double step = 2.0 * M_PI / options_.directions;
  const double half = 0.5 * step;
  for (int k = 0; k < options_.directions; ++k) {
    const double angle = k * step;
    if (excluded_direction && std::abs(grid::NormalizeAngle(angle - *excluded_direction)) < half) continue;
    const Eigen::Vector2d u(std::cos(angle), std::sin(angle));
    // Blocked close by (a wall the rangers have seen): not this way.
    bool blocked = false;
    // Half-cell steps, so that no cell on the way is stepped over.
    for (double d = 0.5 * map.resolution(); d <= 0.5 * options_.goal_distance && !blocked; d += 0.5 * map.resolution()) {
      const Eigen::Vector2i cell = map.CellOf(position + d * u);
      blocked = map.Inside(cell) && map.at(cell) == local_navigation::CellState::kOccupied;
    }
    if (blocked) continue;
    const Eigen::Vector2d goal = position + options_.goal_distance * u;
    const double score = Neighbourhood(goal);
    if (score < best_score - 1e-9) {
      best_score = score;
      best.assign(1, goal);
    } else if (score <= best_score + 1e-9) {
      best.push_back(goal);
    }
  }
  if (best.empty()) {  // walled in on every side as far as the map shows: any way at all
    const double angle = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
    return position + options_.goal_distance * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  return best[std::uniform_int_distribution<std::size_t>(0, best.size() - 1)(rng)];
}

}  // namespace charging_demo
