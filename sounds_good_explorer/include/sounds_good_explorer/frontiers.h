#pragma once

#include <vector>

#include <Eigen/Core>

#include "local_navigation/local_map.h"

namespace sounds_good_explorer {

// Frontier cells (Yamauchi): free cells with an unknown cell among their 8 neighbours. Outside
// the local map counts as unknown, so every free cell on the border is a frontier
// (thesis section 3.3.2). Row by row from cell (0, 0).
std::vector<Eigen::Vector2i> FindFrontiers(const local_navigation::LocalMap& map);

}  // namespace sounds_good_explorer
