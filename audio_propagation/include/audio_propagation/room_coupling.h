#pragma once

// A building's rooms as the acoustic model hears them (world_sim::CoupledRoomsSpec): the map cut
// into rooms and openings (grid/room_segmentation.h), each room given its acoustics, long rooms
// cut into zones along their length (room_zones.h), and the zones' reverberant fields coupled
// through the openings and cross-sections (coupled_rooms.h). Built once per map; a query is two
// cell lookups and a matrix entry. No ROS.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/coupled_rooms.h"
#include "audio_propagation/room_zones.h"
#include "grid/occupancy_map.h"
#include "grid/room_segmentation.h"
#include "world_sim/acoustics.h"

namespace audio_propagation {

class RoomCoupling {
 public:
  // Throws std::invalid_argument naming the option when the segmentation or the energy balance
  // refuses what `acoustics.rooms` asks (a door half-width under a cell, no free space), when a
  // region names no room (it is the larger part of none), or when `acoustics` has no rooms
  // section. `map` must outlive this.
  RoomCoupling(const grid::OccupancyMap& map, const world_sim::Acoustics& acoustics);

  // The room at a world point, or -1 off the map's free space.
  int RoomAt(const Eigen::Vector2d& at) const { return segmentation_.RoomAt(at); }
  // The zone at a world point (index into zones().zones()), or -1 off the map's free space.
  int ZoneAt(const Eigen::Vector2d& at) const { return zones_.ZoneAt(at); }

  // The acoustics of room `room` (index into segmentation().rooms()): its RT60 and its critical
  // distance, from the region covering most of its floor (the room's share of the region's
  // volume or absorption), else the world's RT60 and the room's own volume.
  const world_sim::RoomAcoustics& Acoustics(std::size_t room) const { return rooms_of_.acoustics[room]; }
  // The region (index into the acoustics' regions) that names room `room`, or -1 for none.
  int Region(std::size_t room) const { return rooms_of_.region[room]; }

  // The acoustics of zone `zone`: its room's RT60, and its share of the room's volume (and so
  // of its absorption).
  const world_sim::RoomAcoustics& ZoneAcoustics(std::size_t zone) const { return zone_acoustics_[zone]; }

  struct Rooms {
    std::vector<world_sim::RoomAcoustics> acoustics;
    std::vector<int> region;
  };

  // The reverberant field at `listener` from a source at `source`, in dB against the field the
  // same source would make in its own room were every opening shut (CoupledRooms::
  // RelativeLevelDb). 0 when either point is off the free space (a robot pressed into a wall
  // cell keeps today's single field rather than losing its link).
  double RelativeLevelDb(const Eigen::Vector2d& source, const Eigen::Vector2d& listener) const;

  const grid::RoomSegmentation& segmentation() const { return segmentation_; }
  const RoomZones& zones() const { return zones_; }
  // The energy balance over the zones (indices as zones().zones()).
  const CoupledRooms& field() const { return field_; }

 private:
  grid::RoomSegmentation segmentation_;
  Rooms rooms_of_;
  RoomZones zones_;
  std::vector<world_sim::RoomAcoustics> zone_acoustics_;
  CoupledRooms field_;
};

}  // namespace audio_propagation
