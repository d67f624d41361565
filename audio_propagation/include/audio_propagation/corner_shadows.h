#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "grid/occupancy_map.h"

namespace audio_propagation {

// Where each corner certainly cannot be seen from, built once per map so that a step can skip
// most line-of-sight walks from a listener to the corners.
//
// Around each corner the directions are cut into sectors. A sector is shadowed beyond a
// distance R when every ray from the corner inside it passes through the interior of some
// blocking cell within R: a point in that sector farther than R from the corner is then hidden
// from it under the exact line-of-sight rules (grid/line_of_sight.h), because the segment enters
// a blocking cell. Sectors are filled by taking boxes of wall cells nearest first and marking
// the directions that each box's silhouette covers with a margin, so that rays grazing a box's
// corner or face, which the exact rules let pass, are never counted as covered. The test answers
// "hidden" or "don't know"; callers walk the line for "don't know", so results stay exact.
// Most walks of a step are skipped (those left are mostly corners in sight), for a one-off cost
// when the model is built; the figures measured on the thesis's map are in docs/audio_link.md.
//
// Memory: 4 bytes per sector per corner (kSectors sectors): 12 MB for the hospital map.
class CornerShadows {
 public:
  static constexpr int kSectors = 4096;

  // `corners`: grid vertices in cell coordinates. `threads` > 1 splits the corners over threads.
  CornerShadows(const grid::OccupancyMap& map, const std::vector<Eigen::Vector2d>& corners,
                int threads = 1);

  // True when `point` (cell coordinates) certainly cannot see corner `k`. False means unknown.
  bool Hidden(std::size_t k, const Eigen::Vector2d& point) const;

  std::size_t size() const { return corners_.size(); }
  // Fraction of (corner, sector) entries that have a finite shadow distance; for reports.
  double CoveredFraction() const;

 private:
  // A rectangle of blocking cells [x0, x1) x [y0, y1); `wall` when it holds a cell next to free
  // space. Walls are covered box by box rather than cell by cell: far fewer silhouettes, at the
  // price of shadow distances up to a box diagonal longer.
  struct Box {
    int x0, y0, x1, y1;
    bool wall;
  };
  static constexpr int kBoxSide = 8;  // cells
  static std::vector<Box> WallBoxes(const grid::OccupancyMap& map);
  void BuildCorner(std::size_t k, const std::vector<Box>& boxes,
                   std::vector<float>& sub_far, std::vector<int>& next_open);

  std::vector<Eigen::Vector2d> corners_;
  std::vector<float> shadow_;  // shadow_[k * kSectors + s]: cells; +inf where never covered
};

// A cheap angle substitute, monotonic in the true angle of (x, y) and in [0, 4): 0 along +x,
// 1 along +y, 2 along -x, 3 along -y. (x, y) must not be (0, 0).
double PseudoAngle(double x, double y);

}  // namespace audio_propagation
