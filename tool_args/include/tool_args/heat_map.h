#pragma once

#include <string>
#include <vector>

namespace multirobot_audio::tools {

// Maps of one quantity side by side in a PNG (OpenCV): each panel a grid of values (row 0 at the
// bottom, as a map's), coloured from `low` to `high` on one shared scale (viridis), NaN drawn
// black (a wall, no path), a title over each and a colour bar with the unit.
struct HeatPanel {
  std::string title;
  int width = 0, height = 0;   // cells
  std::vector<double> values;  // width x height, row-major from the bottom row
};
struct HeatMaps {
  std::string unit;
  double low = 0.0, high = 1.0;
  int pixels_per_cell = 4;
  std::vector<HeatPanel> panels;
};
// Throws std::invalid_argument for a panel whose values do not fill it or a scale with
// high <= low, std::runtime_error naming the file when it cannot be written.
void WriteHeatMaps(const std::string& path, const HeatMaps& maps);

}  // namespace multirobot_audio::tools
