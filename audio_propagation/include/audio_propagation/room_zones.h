#pragma once

// A long room's reverberant field is not one diffuse field: down a corridor it falls by about a
// dB a metre (Kang's corridor measurements; the diffusion equation of Valeau, Picaut and Billon).
// The rooms of a segmentation are cut here into zones the coupled-room balance can treat as
// diffuse: a room much longer than it is wide is cut across its length, every
// CorridorZoneLength, into zones coupled through the corridor's cross-section. Such a chain
// falls as the diffusion equation does: zones of length s with absorption alpha P s (P the
// perimeter of the cross-section A_c) joined through A_c decay by sqrt(alpha P / (A_c s)) per
// metre in the steady state, the diffusion equation (D = c l / 3, l = 4 A_c / P the mean free
// path) by (P / A_c) sqrt(3 alpha) / 4; the two agree for s = 16 A_c / (3 P), whatever alpha is.
// Any other room is one zone, so a building of ordinary rooms couples exactly as its rooms do.
// No ROS.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/coupled_rooms.h"
#include "grid/occupancy_map.h"
#include "grid/room_segmentation.h"

namespace audio_propagation {

// The length of the zones a corridor `width` wide under a ceiling `height` high is cut into,
// 16 A_c / (3 P): 4/3 of the mean free path of its cross-section.
double CorridorZoneLength(double width, double height);

struct RoomZoneOptions {
  double ceiling_height = 2.7;  // m: a room's height, for the cross-sections within it
  double door_height = 2.1;     // m: the openings between rooms, as the segmentation measured their widths
  // A room is cut when its length along the floor exceeds this many of its mean widths
  // (area / length): corridors and long halls, not ordinary rooms. 0: no room is cut.
  double corridor_elongation = 3.0;
  double min_zone_area = 1.0;   // m^2: pieces smaller than this join the zone beside them
};

class RoomZones {
 public:
  // Throws std::invalid_argument naming the option for a height not above 0, or an elongation
  // neither 0 nor at least 1.
  RoomZones(const grid::OccupancyMap& map, const grid::RoomSegmentation& rooms, const RoomZoneOptions& options);

  struct Zone {
    int room = 0;        // index into the segmentation's rooms
    double area = 0.0;   // m^2 of free floor
    double share = 1.0;  // of its room's floor
  };

  // The zone at a world point, or -1 off the segmentation's rooms.
  int ZoneAt(const Eigen::Vector2d& world) const;
  const std::vector<Zone>& zones() const { return zones_; }
  // Where zones meet: within a room its cross-section up to the ceiling; between rooms each
  // opening of the segmentation (width x door height), shared among the zones it borders.
  const std::vector<RoomOpening>& openings() const { return openings_; }
  // How many zones room `room` is cut into.
  int ZonesOf(std::size_t room) const { return zones_of_[room]; }

 private:
  // The openings between the zones once they are labelled (room_width: each cut room's mean
  // width, 0 for a room left whole).
  void Connect(const grid::RoomSegmentation& rooms, const std::vector<double>& room_width, const RoomZoneOptions& o);

  const grid::OccupancyMap& map_;
  std::vector<int> labels_;  // per cell: zone, -1 off the rooms
  std::vector<Zone> zones_;
  std::vector<int> zones_of_;
  std::vector<RoomOpening> openings_;
};

}  // namespace audio_propagation
