#include "sounds_good_explorer/frontiers.h"

namespace sounds_good_explorer {

std::vector<Eigen::Vector2i> FindFrontiers(const local_navigation::LocalMap& map) {
  std::vector<Eigen::Vector2i> frontiers;
  const int n = map.size();
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      if (map.at({x, y}) != local_navigation::CellState::kFree) continue;
      bool frontier = false;
      for (int dy = -1; dy <= 1 && !frontier; ++dy) {
        for (int dx = -1; dx <= 1 && !frontier; ++dx) {
          const Eigen::Vector2i nb(x + dx, y + dy);
          frontier = !map.Inside(nb) || map.at(nb) == local_navigation::CellState::kUnknown;
        }
      }
      if (frontier) frontiers.emplace_back(x, y);
    }
  }
  return frontiers;
}

}  // namespace sounds_good_explorer
