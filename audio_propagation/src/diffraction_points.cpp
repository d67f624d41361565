#include "audio_propagation/diffraction_points.h"

#include <array>

namespace audio_propagation {
namespace {

using Pattern = std::array<std::array<int, 3>, 3>;  // [row from top][column], 1 = blocks

// Row-major from the top row, matching the picture; converted to codes with y pointing up.
std::uint16_t ToCode(const Pattern& p) {
  std::uint16_t code = 0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (p[r][c]) code |= static_cast<std::uint16_t>(1u << ((2 - r) * 3 + c));
    }
  }
  return code;
}

Pattern Rotate(const Pattern& p) {
  Pattern q{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) q[c][2 - r] = p[r][c];
  return q;
}

Pattern Mirror(const Pattern& p) {
  Pattern q{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) q[r][2 - c] = p[r][c];
  return q;
}

// Codes whose (free) centre cannot bend a shortest path.
std::array<bool, 512> BuildNonDiffractionTable() {
  const std::array<Pattern, 5> bases = {{
      {{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}},  // empty
      {{{1, 1, 1}, {0, 0, 0}, {0, 0, 0}}},  // straight wall
      {{{1, 1, 1}, {1, 0, 0}, {1, 0, 0}}},  // inside corner
      {{{1, 1, 1}, {0, 0, 0}, {1, 1, 1}}},  // one-cell corridor
      {{{1, 1, 1}, {1, 0, 1}, {1, 0, 1}}},  // dead end: closed on three sides
  }};
  std::array<bool, 512> table{};
  for (Pattern p : bases) {
    for (int m = 0; m < 2; ++m) {
      for (int r = 0; r < 4; ++r) {
        table[ToCode(p)] = true;
        p = Rotate(p);
      }
      p = Mirror(p);
    }
  }
  return table;
}

}  // namespace

std::optional<DiffractionRule> ParseDiffractionRule(const std::string& name) {
  if (name == "masks") return DiffractionRule::kMasks;
  if (name == "convex_corners") return DiffractionRule::kConvexCorners;
  return std::nullopt;
}

const char* DiffractionRuleName(DiffractionRule rule) {
  return rule == DiffractionRule::kMasks ? "masks" : "convex_corners";
}

std::uint16_t NeighbourhoodCode(const grid::OccupancyMap& map, int i, int j) {
  std::uint16_t code = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (map.Blocks(i + dx, j + dy)) code |= static_cast<std::uint16_t>(1u << ((dy + 1) * 3 + (dx + 1)));
    }
  }
  return code;
}

bool IsDiffractionCode(std::uint16_t code, DiffractionRule rule) {
  auto blocks = [code](int dx, int dy) { return (code >> ((dy + 1) * 3 + (dx + 1))) & 1u; };
  if (blocks(0, 0)) return false;  // only free cells carry sound
  if (rule == DiffractionRule::kMasks) {
    static const std::array<bool, 512> kNon = BuildNonDiffractionTable();
    return !kNon[code];
  }
  for (int dy : {-1, 1}) {
    for (int dx : {-1, 1}) {
      if (blocks(dx, dy) && !blocks(dx, 0) && !blocks(0, dy)) return true;
    }
  }
  return false;
}

std::vector<Eigen::Vector2i> FindDiffractionPoints(const grid::OccupancyMap& map, DiffractionRule rule) {
  std::vector<Eigen::Vector2i> points;
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      if (map.at(i, j) != grid::Cell::kFree) continue;
      if (IsDiffractionCode(NeighbourhoodCode(map, i, j), rule)) points.emplace_back(i, j);
    }
  }
  return points;
}

std::vector<Corner> CornerVertices(const grid::OccupancyMap& map,
                                   const std::vector<Eigen::Vector2i>& points) {
  std::vector<Corner> out;
  std::vector<bool> seen(static_cast<std::size_t>(map.width() + 1) * (map.height() + 1), false);
  for (const Eigen::Vector2i& c : points) {
    for (int vy = c.y(); vy <= c.y() + 1; ++vy) {
      for (int vx = c.x(); vx <= c.x() + 1; ++vx) {
        const std::size_t key = static_cast<std::size_t>(vy) * (map.width() + 1) + vx;
        if (seen[key]) continue;
        const bool sw = map.Blocks(vx - 1, vy - 1), se = map.Blocks(vx, vy - 1);
        const bool nw = map.Blocks(vx - 1, vy), ne = map.Blocks(vx, vy);
        if (sw + se + nw + ne != 1) continue;
        seen[key] = true;
        out.push_back({Eigen::Vector2d(vx, vy), (se || ne) ? 1 : -1, (nw || ne) ? 1 : -1});
      }
    }
  }
  return out;
}

}  // namespace audio_propagation
