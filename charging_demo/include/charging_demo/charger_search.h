#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <utility>

#include <Eigen/Core>

#include "local_navigation/local_map.h"

namespace charging_demo {

struct SearchOptions {
  double cell = 1.0;           // m: size of the cells whose visits are counted (odom frame)
  double goal_distance = 4.0;  // m: how far ahead each goal is set
  int directions = 16;         // candidate goals, evenly spread round the robot
  double hold = 10.0;          // s a goal is kept before choosing again
  // s of visits a goal the robot could not get to counts as: beyond a wall, outside the
  // building, places never visited would otherwise draw the search for ever.
  double unreachable_penalty = 60.0;
};

void ValidateOptions(const SearchOptions& options);

// Looking for a charger with no map: random wandering keeps a robot in the room it is in for a
// long time (a robot that started far off ran flat that way). This search remembers how long
// the robot has spent in each cell of a coarse odom-frame grid and sends it, goal after goal,
// towards the least visited surroundings, so it leaves places it has already looked at.
// Odometry drift blurs old counts, which only makes the search more random. Deterministic for
// the generator it is given.
class ChargerSearch {
 public:
  explicit ChargerSearch(const SearchOptions& options);

  // The robot spent `dt` s at `position` (odom frame).
  void Visit(const Eigen::Vector2d& position, double dt);
  // The robot could not get to `goal`: its cell counts as visited for unreachable_penalty s more.
  void MarkUnreachable(const Eigen::Vector2d& goal);
  // Seconds spent in the cell holding `position`.
  double Visits(const Eigen::Vector2d& position) const;

  // A goal goal_distance from `position` in the direction whose neighbourhood (3 x 3 cells) has
  // been visited least, skipping directions the local map shows blocked within the first half
  // of the way; ties are broken at random. `excluded_direction` (rad, odom frame) is skipped too
  // (the way that just failed).
  Eigen::Vector2d ChooseGoal(const Eigen::Vector2d& position, const local_navigation::LocalMap& map,
                             std::mt19937& rng,
                             std::optional<double> excluded_direction = std::nullopt) const;

  const SearchOptions& options() const { return options_; }

 private:
  std::pair<int, int> CellOf(const Eigen::Vector2d& position) const;
  double Neighbourhood(const Eigen::Vector2d& position) const;

  SearchOptions options_;
  std::map<std::pair<int, int>, double> visits_;  // s per cell
};

}  // namespace charging_demo
