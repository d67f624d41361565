#include "sounds_good_explorer/frontiers.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "local_navigation/local_map.h"

namespace sounds_good_explorer {
namespace {

using local_navigation::CellState;
using local_navigation::LocalMap;
using local_navigation::LocalMapOptions;

bool Contains(const std::vector<Eigen::Vector2i>& cells, const Eigen::Vector2i& c) {
  return std::find(cells.begin(), cells.end(), c) != cells.end();
}

TEST(Frontiers, FreeCellsNextToUnknownAndOnTheBorder) {
  LocalMap map(LocalMapOptions{5, 1.0, 100.0});
  map.Recentre({0.5, 0.5});
  // Row y = 2 free from x = 0 to 3; (1, 1) free, (1, 3) occupied; everything else unknown.
  // Then fill the 3 x 3 block around (2, 2)... by hand:
  //   y=4  ? ? ? ? ?
  //   y=3  ? # F F ?
  //   y=2  F F F F ?
  //   y=1  ? F F F ?
  //   y=0  ? ? ? ? ?
  for (int x = 0; x < 4; ++x) map.Set({x, 2}, CellState::kFree, 0.0);
  for (int x = 1; x < 4; ++x) map.Set({x, 1}, CellState::kFree, 0.0);
  map.Set({1, 3}, CellState::kOccupied, 0.0);
  map.Set({2, 3}, CellState::kFree, 0.0);
  map.Set({3, 3}, CellState::kFree, 0.0);
  const std::vector<Eigen::Vector2i> f = FindFrontiers(map);
  // Every free cell here touches unknown except (2, 2): its 8 neighbours are all known.
  EXPECT_FALSE(Contains(f, {2, 2}));
  for (const Eigen::Vector2i& c : {Eigen::Vector2i(0, 2), Eigen::Vector2i(1, 2),
                                  Eigen::Vector2i(3, 2), Eigen::Vector2i(1, 1),
                                  Eigen::Vector2i(2, 1), Eigen::Vector2i(3, 1),
                                  Eigen::Vector2i(2, 3), Eigen::Vector2i(3, 3)})
    EXPECT_TRUE(Contains(f, c)) << c.transpose();
  EXPECT_FALSE(Contains(f, {1, 3}));  // occupied cells are never frontiers
  EXPECT_EQ(f.size(), 8u);
}

TEST(Frontiers, BorderCellsAreFrontiersEvenWhenAllNeighboursInsideAreKnown) {
  LocalMap map(LocalMapOptions{3, 1.0, 100.0});
  map.Recentre({0.5, 0.5});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) map.Set({x, y}, CellState::kFree, 0.0);
  const std::vector<Eigen::Vector2i> f = FindFrontiers(map);
  EXPECT_EQ(f.size(), 8u);  // all but the centre
  EXPECT_FALSE(Contains(f, {1, 1}));
}

}  // namespace
}  // namespace sounds_good_explorer
