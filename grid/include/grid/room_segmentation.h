#pragma once

// The rooms of a floor plan and the openings between them, from its occupancy map, by the
// distance-transform method of ipa_room_segmentation (Bormann et al., "Room segmentation:
// survey, implementation, and analysis", ICRA 2016): free space thinned by the half-width of the
// widest doorway falls apart into room cores; the cores then grow back together over all of the
// free space, each cell joining the core it is nearest to along the floor; where two rooms'
// growths meet lies an opening between them. A passage wider than two half-widths (an open-plan
// floor, a hall opening on a corridor without a door) keeps its two sides one room; a core
// smaller than the smallest room (an alcove, a gap between furniture) joins its neighbours.
// No ROS.
#include <vector>

#include <Eigen/Core>

#include "grid/occupancy_map.h"

namespace grid {

struct RoomSegmentationOptions {
  double door_half_width = 0.6;  // m: openings up to twice this wide (a 1.2 m double door) divide rooms
  double min_room_area = 1.0;    // m^2: the smallest core kept as a room
  double max_obstacle_size = 1.0;  // m: free-standing obstacles no longer than this (pillars, tables) divide no room
};

struct SegmentedRoom {
  double area = 0.0;           // m^2 of free floor
  Eigen::Vector2d centroid;    // world, m
};

// Where rooms `a` < `b` meet: a doorway, or where a corridor joins a hall.
struct SegmentedOpening {
  int a = 0;
  int b = 0;
  double width = 0.0;        // m, along the line where they meet
  Eigen::Vector2d center;    // world, m
};

class RoomSegmentation {
 public:
  // Throws std::invalid_argument naming the option for a door half-width under one cell of the
  // map or not finite, a negative minimum area, or a map with no free space.
  RoomSegmentation(const OccupancyMap& map, const RoomSegmentationOptions& options);

  // The room at a world point: its index in rooms(), or -1 off the map's free space.
  int RoomAt(const Eigen::Vector2d& world) const;
  // The room of cell (i, j), or -1 where the cell is blocked (in bounds only).
  int RoomOfCell(int i, int j) const { return labels_[static_cast<std::size_t>(j) * width_ + i]; }

  const std::vector<SegmentedRoom>& rooms() const { return rooms_; }
  const std::vector<SegmentedOpening>& openings() const { return openings_; }

 private:
  const OccupancyMap& map_;
  int width_ = 0;
  std::vector<int> labels_;  // per cell: room index, -1 blocked
  std::vector<SegmentedRoom> rooms_;
  std::vector<SegmentedOpening> openings_;
};

}  // namespace grid
