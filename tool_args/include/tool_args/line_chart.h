#pragma once

#include <string>
#include <vector>

namespace multirobot_audio::tools {

// A PNG line chart (OpenCV): several series over a shared x axis, each with a colour and a
// dash style, and a legend. y runs from y_min to y_max.
struct LineSeries {
  std::string label;
  std::vector<double> x, y;
  int colour = 0;  // index into a fixed palette
  enum class Style { kSolid, kDashed, kDotted } style = Style::kSolid;
};
struct LineChart {
  std::string title, x_label, y_label;
  double y_min = 0.0, y_max = 100.0;
  std::vector<LineSeries> series;
};
// Throws std::runtime_error naming the file when it cannot be written.
void WriteLineChart(const std::string& path, const LineChart& chart);

}  // namespace multirobot_audio::tools
