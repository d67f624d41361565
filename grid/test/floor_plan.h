#pragma once

// Floor plans drawn in metres for tests of rooms (grid's segmentation, audio_propagation's
// coupled rooms): everything starts free, walls are filled boxes, doors boxes cleared again.
#include "grid/occupancy_map.h"

namespace grid::test {

class Floor {
 public:
  // A floor `width` x `height` m of cells `resolution` m, walled 0.1 m thick all round.
  Floor(double width, double height, double resolution = 0.05)
      : map_(static_cast<int>(width / resolution + 0.5), static_cast<int>(height / resolution + 0.5), resolution) {
    Wall(0, 0, width, 0.1);
    Wall(0, height - 0.1, width, height);
    Wall(0, 0, 0.1, height);
    Wall(width - 0.1, 0, width, height);
  }
  Floor& Wall(double x0, double y0, double x1, double y1) { return Fill(x0, y0, x1, y1, Cell::kOccupied); }
  Floor& Door(double x0, double y0, double x1, double y1) { return Fill(x0, y0, x1, y1, Cell::kFree); }
  const OccupancyMap& map() const { return map_; }

 private:
  Floor& Fill(double x0, double y0, double x1, double y1, Cell c) {
    for (int j = 0; j < map_.height(); ++j) {
      for (int i = 0; i < map_.width(); ++i) {
        const Eigen::Vector2d p = map_.CellCenter(i, j);
        if (p.x() >= x0 && p.x() <= x1 && p.y() >= y0 && p.y() <= y1) map_.set(i, j, c);
      }
    }
    return *this;
  }
  OccupancyMap map_;
};

}  // namespace grid::test
