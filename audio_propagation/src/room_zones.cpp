#include "audio_propagation/room_zones.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

namespace audio_propagation {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("room zones: " + what);
}

// Distances (in cells) along the floor of one room from `start`, moving to the 8 neighbours
// (diagonals sqrt(2)); cells outside the room stay infinite.
std::vector<double> FloorDistances(const grid::RoomSegmentation& rooms, int width, int height, int room, int start) {
  std::vector<double> d(static_cast<std::size_t>(width) * height, std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  d[static_cast<std::size_t>(start)] = 0.0;
  open.push({0.0, start});
  while (!open.empty()) {
    const auto [dist, k] = open.top();
    open.pop();
    if (dist > d[static_cast<std::size_t>(k)]) continue;
    const int i = k % width, j = k / width;
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        const int ni = i + di, nj = j + dj;
        if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= width || nj >= height) continue;
        if (rooms.RoomOfCell(ni, nj) != room) continue;
        const double next = dist + (di != 0 && dj != 0 ? M_SQRT2 : 1.0);
        const std::size_t n = static_cast<std::size_t>(nj) * width + ni;
        if (next < d[n]) {
          d[n] = next;
          open.push({next, static_cast<int>(n)});
        }
      }
    }
  }
  return d;
}

// Each room's cells, and the band along its length each cell lies in.
struct Bands {
  std::vector<std::vector<int>> cells;  // per room
  std::vector<int> band;                // per cell: 0 in a room left whole, -1 off the rooms
  std::vector<double> width;            // per room: its mean width where it is cut, else 0
};

// A room longer than o.corridor_elongation of its mean widths cut across its length, every
// CorridorZoneLength along its floor.
Bands CutAlongCorridors(const grid::OccupancyMap& map, const grid::RoomSegmentation& rooms, const RoomZoneOptions& o) {
  const int width = map.width(), height = map.height();
  const double res = map.resolution();
  const std::size_t n_rooms = rooms.rooms().size();
  Bands b;
  b.cells.resize(n_rooms);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const int room = rooms.RoomOfCell(i, j);
      if (room >= 0) b.cells[static_cast<std::size_t>(room)].push_back(j * width + i);
    }
  }
  b.band.assign(static_cast<std::size_t>(width) * height, -1);
  b.width.assign(n_rooms, 0.0);
  for (std::size_t r = 0; r < n_rooms; ++r) {
    const std::vector<int>& cells = b.cells[r];
    for (int c : cells) b.band[static_cast<std::size_t>(c)] = 0;
    if (cells.empty() || o.corridor_elongation == 0.0) continue;
    const int room = static_cast<int>(r);
    // The room's length: the farthest cell from the cell farthest from any of its cells (a
    // piece the room's own floor does not reach, behind a pillar the segmentation looked
    // through, is left out, and is a zone of its own below).
    auto farthest = [&](const std::vector<double>& d) {
      int best = cells.front();
      for (int c : cells) {
        if (std::isfinite(d[static_cast<std::size_t>(c)]) && d[static_cast<std::size_t>(c)] > d[static_cast<std::size_t>(best)]) {
          best = c;
        }
      }
      return best;
    };
    const int end = farthest(FloorDistances(rooms, width, height, room, cells.front()));
    const std::vector<double> along = FloorDistances(rooms, width, height, room, end);
    const double length = (along[static_cast<std::size_t>(farthest(along))] + 1.0) * res;
    const double area = static_cast<double>(cells.size()) * res * res;
    const double mean_width = area / length;
    if (length < o.corridor_elongation * mean_width) continue;
    const int bands = static_cast<int>(std::lround(length / CorridorZoneLength(mean_width, o.ceiling_height)));
    if (bands < 2) continue;
    b.width[r] = mean_width;
    const double step = length / bands;
    for (int c : cells) {
      const double d = along[static_cast<std::size_t>(c)];
      b.band[static_cast<std::size_t>(c)] = std::isfinite(d) ? std::min(bands - 1, static_cast<int>(d * res / step)) : 0;
    }
  }
  return b;
}

// Zones before their crumbs are joined: a room left whole is one; a cut room's are the connected
// pieces of its bands.
struct Pieces {
  std::vector<int> labels;   // per cell: piece, -1 off the rooms
  std::vector<int> room_of;  // per piece
  std::vector<int> cells;    // per piece: how many
};

Pieces ConnectedPieces(const grid::RoomSegmentation& rooms, int width, int height, const Bands& b) {
  Pieces p;
  p.labels.assign(static_cast<std::size_t>(width) * height, -1);
  const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
  for (std::size_t r = 0; r < b.cells.size(); ++r) {
    if (b.width[r] == 0.0 && !b.cells[r].empty()) {
      for (int c : b.cells[r]) p.labels[static_cast<std::size_t>(c)] = static_cast<int>(p.room_of.size());
      p.room_of.push_back(static_cast<int>(r));
      p.cells.push_back(static_cast<int>(b.cells[r].size()));
      continue;
    }
    for (int start : b.cells[r]) {
      if (p.labels[static_cast<std::size_t>(start)] >= 0) continue;
      const int piece = static_cast<int>(p.room_of.size());
      p.room_of.push_back(static_cast<int>(r));
      p.cells.push_back(0);
      std::deque<int> queue{start};
      p.labels[static_cast<std::size_t>(start)] = piece;
      while (!queue.empty()) {
        const int k = queue.front();
        queue.pop_front();
        ++p.cells.back();
        for (int n = 0; n < 4; ++n) {
          const int ni = k % width + di[n], nj = k / width + dj[n];
          if (ni < 0 || nj < 0 || ni >= width || nj >= height) continue;
          const int m = nj * width + ni;
          if (p.labels[static_cast<std::size_t>(m)] >= 0 || rooms.RoomOfCell(ni, nj) != static_cast<int>(r) ||
              b.band[static_cast<std::size_t>(m)] != b.band[static_cast<std::size_t>(k)]) {
            continue;
          }
          p.labels[static_cast<std::size_t>(m)] = piece;
          queue.push_back(m);
        }
      }
    }
  }
  return p;
}

// each(a, b) for every two side-by-side cells, both on a label (a the left or lower one).
template <typename Each>
void ForEachEdge(const std::vector<int>& labels, int width, int height, Each&& each) {
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const int a = labels[static_cast<std::size_t>(j) * width + i];
      if (a < 0) continue;
      if (i + 1 < width && labels[static_cast<std::size_t>(j) * width + i + 1] >= 0) {
        each(a, labels[static_cast<std::size_t>(j) * width + i + 1]);
      }
      if (j + 1 < height && labels[static_cast<std::size_t>(j + 1) * width + i] >= 0) {
        each(a, labels[static_cast<std::size_t>(j + 1) * width + i]);
      }
    }
  }
}

// The piece each piece joins: itself, or for a crumb of a band under `min_cells` (a corner cut
// off by the bands' edges) the piece of its room it shares the most edge with.
std::vector<int> CrumbsJoined(const Pieces& p, int width, int height, int min_cells) {
  std::vector<int> joined(p.room_of.size());
  for (std::size_t z = 0; z < joined.size(); ++z) joined[z] = static_cast<int>(z);
  std::vector<std::map<int, int>> shared(p.room_of.size());
  ForEachEdge(p.labels, width, height, [&](int a, int b) {
    if (a == b || p.room_of[static_cast<std::size_t>(a)] != p.room_of[static_cast<std::size_t>(b)]) return;
    ++shared[static_cast<std::size_t>(a)][b];
    ++shared[static_cast<std::size_t>(b)][a];
  });
  for (std::size_t z = 0; z < joined.size(); ++z) {
    if (p.cells[z] >= min_cells || shared[z].empty()) continue;
    int best = -1, most = 0;
    for (const auto& [other, count] : shared[z]) {
      if (count > most && p.cells[static_cast<std::size_t>(other)] >= min_cells) best = other, most = count;
    }
    if (best >= 0) joined[z] = best;
  }
  return joined;
}

}  // namespace

double CorridorZoneLength(double width, double height) {
  return 16.0 * width * height / (3.0 * 2.0 * (width + height));
}

RoomZones::RoomZones(const grid::OccupancyMap& map, const grid::RoomSegmentation& rooms, const RoomZoneOptions& o)
    : map_(map) {
  Require(o.ceiling_height > 0.0 && std::isfinite(o.ceiling_height), "ceiling_height must be a positive number of m");
  Require(o.door_height > 0.0 && std::isfinite(o.door_height), "door_height must be a positive number of m");
  Require((o.corridor_elongation == 0.0 || o.corridor_elongation >= 1.0) && std::isfinite(o.corridor_elongation),
          "corridor_elongation must be 0 (no room cut) or at least 1");
  Require(o.min_zone_area >= 0.0 && std::isfinite(o.min_zone_area), "min_zone_area must be >= 0 m^2");
  const int width = map.width(), height = map.height();
  const double res = map.resolution();
  const Bands bands = CutAlongCorridors(map, rooms, o);
  Pieces pieces = ConnectedPieces(rooms, width, height, bands);
  const std::vector<int> joined =
      CrumbsJoined(pieces, width, height, static_cast<int>(std::ceil(o.min_zone_area / (res * res))));

  // Number the zones left, room by room.
  std::vector<int> id(pieces.room_of.size(), -1);
  zones_of_.assign(rooms.rooms().size(), 0);
  for (std::size_t z = 0; z < id.size(); ++z) {
    if (joined[z] != static_cast<int>(z)) continue;
    id[z] = static_cast<int>(zones_.size());
    zones_.push_back({pieces.room_of[z], 0.0, 1.0});
    ++zones_of_[static_cast<std::size_t>(pieces.room_of[z])];
  }
  labels_ = std::move(pieces.labels);
  std::vector<int> zone_cells(zones_.size(), 0);
  for (int& label : labels_) {
    if (label < 0) continue;
    label = id[static_cast<std::size_t>(joined[static_cast<std::size_t>(label)])];
    ++zone_cells[static_cast<std::size_t>(label)];
  }
  for (std::size_t z = 0; z < zones_.size(); ++z) {
    const auto room = static_cast<std::size_t>(zones_[z].room);
    zones_[z].area = zone_cells[z] * res * res;
    // A room left whole is exactly its room (no rounding in its share).
    zones_[z].share = zones_of_[room] == 1 ? 1.0 : static_cast<double>(zone_cells[z]) / bands.cells[room].size();
  }
  Connect(rooms, bands.width, o);
}

// Where zones meet: edges within a room are its cross-section; edges between rooms share out the
// segmentation's openings between those rooms.
void RoomZones::Connect(const grid::RoomSegmentation& rooms, const std::vector<double>& room_width,
                        const RoomZoneOptions& o) {
  const double res = map_.resolution();
  std::map<std::pair<int, int>, int> within, between;
  ForEachEdge(labels_, map_.width(), map_.height(), [&](int a, int b) {
    if (a == b) return;
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    ++(zones_[static_cast<std::size_t>(a)].room == zones_[static_cast<std::size_t>(b)].room ? within : between)[key];
  });
  for (const auto& [pair, count] : within) {
    // The cells' edges step along a boundary that runs slantwise (the bands are arcs near the
    // end they are measured from), which would make it longer than the corridor is wide.
    const double across = room_width[static_cast<std::size_t>(zones_[static_cast<std::size_t>(pair.first)].room)];
    openings_.push_back({static_cast<std::size_t>(pair.first), static_cast<std::size_t>(pair.second),
                         std::min(count * res, across) * o.ceiling_height});
  }
  std::map<std::pair<int, int>, double> door_area;  // per pair of rooms
  for (const grid::SegmentedOpening& opening : rooms.openings()) {
    door_area[{std::min(opening.a, opening.b), std::max(opening.a, opening.b)}] += opening.width * o.door_height;
  }
  std::map<std::pair<int, int>, int> room_edges;
  auto rooms_of = [&](const std::pair<int, int>& zones) {
    const int a = zones_[static_cast<std::size_t>(zones.first)].room, b = zones_[static_cast<std::size_t>(zones.second)].room;
    return std::pair<int, int>(std::min(a, b), std::max(a, b));
  };
  for (const auto& [pair, count] : between) room_edges[rooms_of(pair)] += count;
  for (const auto& [pair, count] : between) {
    const auto door = door_area.find(rooms_of(pair));
    if (door == door_area.end()) continue;  // touching at a corner, no opening the segmentation found
    openings_.push_back({static_cast<std::size_t>(pair.first), static_cast<std::size_t>(pair.second),
                         door->second * count / room_edges[rooms_of(pair)]});
  }
}

int RoomZones::ZoneAt(const Eigen::Vector2d& world) const {
  const Eigen::Vector2i c = map_.WorldToCell(world);
  if (!map_.InBounds(c.x(), c.y())) return -1;
  return labels_[static_cast<std::size_t>(c.y()) * map_.width() + c.x()];
}

}  // namespace audio_propagation
