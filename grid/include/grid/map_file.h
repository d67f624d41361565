#pragma once

#include <string>

#include "grid/occupancy_map.h"

namespace grid {

// Loads a map in map_server's format: a YAML file with `image` (PGM or PNG, relative to the
// YAML file), `resolution` (m/cell), `origin` [x, y, yaw], and optional `negate` (0/1),
// `occupied_thresh`, `free_thresh` and `mode` (only `trinary`). Pixels are classified as
// map_server does: occupancy = (255 - grey) / 255 (grey itself when negated); above
// occupied_thresh is occupied, below free_thresh is free, between is unknown.
// Throws InputError naming the file and field on anything missing or malformed.
OccupancyMap LoadMapFile(const std::string& yaml_path);

}  // namespace grid
