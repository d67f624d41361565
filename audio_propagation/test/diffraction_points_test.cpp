#include "audio_propagation/diffraction_points.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace audio_propagation {
namespace {

// Builds a map from rows of text, top row first: '#' blocks, '.' is free.
grid::OccupancyMap FromText(const std::vector<std::string>& rows) {
  grid::OccupancyMap map(static_cast<int>(rows[0].size()), static_cast<int>(rows.size()), 1.0);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      if (rows[r][c] == '#') map.set(static_cast<int>(c), static_cast<int>(rows.size() - 1 - r), grid::Cell::kOccupied);
    }
  }
  return map;
}

bool IsPoint(const std::vector<std::string>& rows3, DiffractionRule rule) {
  // Pads the 3x3 picture with free cells so that the map edge does not count.
  std::vector<std::string> padded = {".....", "." + rows3[0] + ".", "." + rows3[1] + ".",
                                     "." + rows3[2] + ".", "....."};
  const grid::OccupancyMap map = FromText(padded);
  return IsDiffractionCode(NeighbourhoodCode(map, 2, 2), rule);
}

TEST(DiffractionPoints, MaskClassesThatCannotBendAPath) {
  for (auto rule : {DiffractionRule::kMasks, DiffractionRule::kConvexCorners}) {
    EXPECT_FALSE(IsPoint({"...", "...", "..."}, rule)) << "empty";
    EXPECT_FALSE(IsPoint({"###", "...", "..."}, rule)) << "straight wall";
    EXPECT_FALSE(IsPoint({"..#", "..#", "..#"}, rule)) << "straight wall, rotated";
    EXPECT_FALSE(IsPoint({"###", "#..", "#.."}, rule)) << "inside corner";
    EXPECT_FALSE(IsPoint({"#..", "#..", "###"}, rule)) << "inside corner, reflected";
    EXPECT_FALSE(IsPoint({"###", "...", "###"}, rule)) << "one-cell corridor";
    EXPECT_FALSE(IsPoint({"#.#", "#.#", "#.#"}, rule)) << "vertical corridor";
    EXPECT_FALSE(IsPoint({"###", "#.#", "#.#"}, rule)) << "dead end";
    EXPECT_FALSE(IsPoint({"#.#", "#.#", "###"}, rule)) << "dead end, flipped";
    EXPECT_FALSE(IsPoint({"###", "###", "###"}, rule)) << "full";
    EXPECT_FALSE(IsPoint({"...", ".#.", "..."}, rule)) << "centre blocked";
  }
}

TEST(DiffractionPoints, ConvexCornerIsAPointUnderBothRules) {
  for (auto rule : {DiffractionRule::kMasks, DiffractionRule::kConvexCorners}) {
    EXPECT_TRUE(IsPoint({"#..", "...", "..."}, rule));
    EXPECT_TRUE(IsPoint({"...", "...", "..#"}, rule));
  }
}

TEST(DiffractionPoints, MasksKeepMoreThanConvexCorners) {
  // A wall end that is flush with the centre row: masks keep it, convex corners need a free
  // pair of cells between the centre and the corner.
  EXPECT_TRUE(IsPoint({"##.", "#..", "..."}, DiffractionRule::kMasks));
  EXPECT_FALSE(IsPoint({"##.", "#..", "..."}, DiffractionRule::kConvexCorners));
}

TEST(DiffractionPoints, ABlockHasOnePointOffEachCorner) {
  const grid::OccupancyMap map = FromText({
      "........",
      "........",
      "...##...",
      "...##...",
      "........",
      "........",
  });
  const auto points = FindDiffractionPoints(map, DiffractionRule::kConvexCorners);
  const std::vector<Eigen::Vector2i> expected = {{2, 1}, {5, 1}, {2, 4}, {5, 4}};
  ASSERT_EQ(points.size(), expected.size());
  for (const auto& e : expected) {
    EXPECT_NE(std::find(points.begin(), points.end(), e), points.end()) << e.transpose();
  }
  // Masks also keep the cells beside the block's faces next to its corners.
  EXPECT_GT(FindDiffractionPoints(map, DiffractionRule::kMasks).size(), expected.size());
}

TEST(DiffractionPoints, DiagonalWallIsAStaircaseOfCorners) {
  const grid::OccupancyMap map = FromText({
      "#.......",
      ".#......",
      "..#.....",
      "...#....",
      "....#...",
      ".....#..",
  });
  // Every step of the staircase is a convex corner on both sides.
  EXPECT_GE(FindDiffractionPoints(map, DiffractionRule::kConvexCorners).size(), 8u);
}

TEST(DiffractionPoints, BothRulesBendAtTheSameCorners) {
  const grid::OccupancyMap map = FromText({
      "..........",
      "..###.....",
      "..#.......",
      "..#...##..",
      "......#...",
      "..........",
  });
  const auto masks = CornerVertices(map, FindDiffractionPoints(map, DiffractionRule::kMasks));
  const auto convex = CornerVertices(map, FindDiffractionPoints(map, DiffractionRule::kConvexCorners));
  auto has = [](const std::vector<Corner>& list, const Eigen::Vector2d& p) {
    return std::any_of(list.begin(), list.end(), [&](const Corner& c) { return c.position == p; });
  };
  EXPECT_EQ(masks.size(), convex.size());
  for (const auto& c : convex) EXPECT_TRUE(has(masks, c.position)) << c.position.transpose();
  // The outer corner of the L-shaped wall, at the top right of its top row, is a bend, with the
  // wall below and to the left of it.
  ASSERT_TRUE(has(convex, Eigen::Vector2d(5.0, 5.0)));
  for (const auto& c : convex) {
    if (c.position == Eigen::Vector2d(5.0, 5.0)) {
      EXPECT_EQ(c.qx, -1);
      EXPECT_EQ(c.qy, -1);
      EXPECT_TRUE(c.Tangent({1.0, -1.0}));   // grazing the corner
      EXPECT_FALSE(c.Tangent({-1.0, -1.0}));  // straight into the wall
    }
  }
}

TEST(DiffractionPoints, RuleNames) {
  EXPECT_EQ(ParseDiffractionRule("masks"), DiffractionRule::kMasks);
  EXPECT_EQ(ParseDiffractionRule("convex_corners"), DiffractionRule::kConvexCorners);
  EXPECT_FALSE(ParseDiffractionRule("corners").has_value());
}

}  // namespace
}  // namespace audio_propagation
