#include "audio_propagation/room_coupling.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace audio_propagation {
namespace {

const world_sim::CoupledRoomsSpec& RequireRooms(const world_sim::Acoustics& acoustics) {
  if (!acoustics.rooms) throw std::invalid_argument("room coupling: the acoustics have no rooms section");
  return *acoustics.rooms;
}

grid::RoomSegmentationOptions SegmentationOptions(const world_sim::CoupledRoomsSpec& spec) {
  grid::RoomSegmentationOptions o;
  o.door_half_width = spec.door_half_width;
  o.min_room_area = spec.min_room_area;
  o.max_obstacle_size = spec.max_obstacle_size;
  return o;
}

// A part of a room or region, `share` of its floor: that share of its volume, and so of its
// absorption (r_c^2 goes as A).
world_sim::RoomAcoustics Share(world_sim::RoomAcoustics a, double share) {
  a.volume *= share;
  a.critical_distance *= std::sqrt(share);
  return a;
}

// Each room's acoustics: the region (or the world's room) whose box holds most of its cells'
// centres. A region names its rooms' RT60, and their volume or critical distance for the whole
// region: a room gets its share, by its cells among the region's free ones (the absorption
// area, and so r_c^2 and the volume, shares out with the floor). Elsewhere a room's volume is
// its own floor times the ceiling, so that a small office is as reverberant as its size makes it
// rather than as the whole floor's volume would. A region that is the largest share of no room
// names nothing, which is refused: it would be silently overruled.
RoomCoupling::Rooms RoomsAcoustics(const grid::OccupancyMap& map, const grid::RoomSegmentation& segmentation,
                                   const world_sim::Acoustics& acoustics) {
  const std::size_t n = segmentation.rooms().size();
  // Cells per room and region (region index, or -1 for the world's room), and per region.
  std::vector<std::map<int, int>> votes(n);
  std::vector<int> region_cells(acoustics.regions.size(), 0);
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      const int room = segmentation.RoomOfCell(i, j);
      if (room < 0) continue;
      const Eigen::Vector2d c = map.CellCenter(i, j);
      int region = -1;
      for (std::size_t r = 0; r < acoustics.regions.size(); ++r) {
        if (acoustics.regions[r].Contains(c.x(), c.y())) {
          region = static_cast<int>(r);
          ++region_cells[r];
          break;
        }
      }
      ++votes[static_cast<std::size_t>(room)][region];
    }
  }
  RoomCoupling::Rooms out;
  out.acoustics.resize(n);
  out.region.assign(n, -1);
  std::vector<char> named(acoustics.regions.size(), 0);
  for (std::size_t k = 0; k < n; ++k) {
    int best = -1, most = -1;
    for (const auto& [region, count] : votes[k]) {
      if (count > most) best = region, most = count;
    }
    out.region[k] = best;
    if (best >= 0) {
      const auto r = static_cast<std::size_t>(best);
      named[r] = 1;
      out.acoustics[k] = Share(acoustics.regions[r].room, static_cast<double>(most) / region_cells[r]);
      continue;
    }
    out.acoustics[k].rt60 = acoustics.room.rt60;
    out.acoustics[k].volume = segmentation.rooms()[k].area * acoustics.rooms->ceiling_height;
    out.acoustics[k].critical_distance = 0.0;
  }
  for (std::size_t r = 0; r < named.size(); ++r) {
    if (!named[r]) {
      throw std::invalid_argument("region '" + acoustics.regions[r].name +
                                  "' is the larger part of none of the rooms the map is cut into, so it names "
                                  "none (audio_channel_validate --rooms shows the cut; a door_half_width that "
                                  "divides it from its neighbours, or a box over its room, is expected)");
    }
  }
  return out;
}

std::vector<CoupledRoomSpec> Specs(const std::vector<world_sim::RoomAcoustics>& acoustics) {
  std::vector<CoupledRoomSpec> specs;
  for (std::size_t k = 0; k < acoustics.size(); ++k) {
    // The energy balance wants a room's absorption, from its volume and RT60 (Sabine); a room
    // known by its critical distance instead gives it as r_c^2 = A / (16 pi).
    const world_sim::RoomAcoustics& a = acoustics[k];
    double volume = a.volume;
    if (a.critical_distance > 0.0) {
      const double absorption = 16.0 * M_PI * a.critical_distance * a.critical_distance;
      volume = absorption * kSoundSpeed * a.rt60 / (24.0 * std::log(10.0));
    }
    specs.push_back({"", volume, a.rt60});
  }
  return specs;
}

RoomZoneOptions ZoneOptions(const world_sim::CoupledRoomsSpec& spec) {
  RoomZoneOptions o;
  o.ceiling_height = spec.ceiling_height;
  o.door_height = spec.door_height;
  o.min_zone_area = spec.min_room_area;
  o.corridor_elongation = spec.corridor_elongation;
  return o;
}

// Each zone: its share of its room (a room left whole is exactly itself).
std::vector<world_sim::RoomAcoustics> ZonesAcoustics(const RoomZones& zones, const RoomCoupling::Rooms& rooms) {
  std::vector<world_sim::RoomAcoustics> out;
  for (const RoomZones::Zone& z : zones.zones()) {
    const world_sim::RoomAcoustics& room = rooms.acoustics[static_cast<std::size_t>(z.room)];
    out.push_back(z.share < 1.0 ? Share(room, z.share) : room);
  }
  return out;
}

}  // namespace

RoomCoupling::RoomCoupling(const grid::OccupancyMap& map, const world_sim::Acoustics& acoustics)
    : segmentation_(map, SegmentationOptions(RequireRooms(acoustics))),
      rooms_of_(RoomsAcoustics(map, segmentation_, acoustics)),
      zones_(map, segmentation_, ZoneOptions(*acoustics.rooms)),
      zone_acoustics_(ZonesAcoustics(zones_, rooms_of_)),
      field_(Specs(zone_acoustics_), zones_.openings()) {}

double RoomCoupling::RelativeLevelDb(const Eigen::Vector2d& source, const Eigen::Vector2d& listener) const {
  const int s = zones_.ZoneAt(source), l = zones_.ZoneAt(listener);
  if (s < 0 || l < 0) return 0.0;
  return field_.RelativeLevelDb(static_cast<std::size_t>(s), static_cast<std::size_t>(l));
}

}  // namespace audio_propagation
