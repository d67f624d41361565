#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sounds_good_explorer {

// One method's means and 95 % interval half-widths, one per x position (NaN: no value).
struct IntervalSeries {
  std::string name;
  std::array<std::uint8_t, 3> rgb{0, 0, 0};
  std::vector<double> mean;
  std::vector<double> half_width;
};

// A chart like the thesis's Figure 3.6: at each x position, each series' mean as a dot with its
// interval as an error bar, series side by side, with a legend.
struct IntervalChart {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<std::string> x_ticks;
  std::vector<IntervalSeries> series;
};

// Draws the chart and writes it as PNG; throws std::runtime_error naming the path on failure.
void WriteIntervalChart(const std::string& path, const IntervalChart& chart);

}  // namespace sounds_good_explorer
