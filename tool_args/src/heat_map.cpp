#include "tool_args/heat_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace multirobot_audio::tools {
namespace {

const cv::Scalar kInk(40, 40, 40);
constexpr int kMargin = 30, kTitle = 24, kBar = 18;

void Text(cv::Mat& image, const std::string& text, cv::Point at) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, kInk, 1, cv::LINE_AA);
}

// Where `v` falls on the scale, 0 to 255.
std::uint8_t Level(double v, double low, double high) {
  return static_cast<std::uint8_t>(std::clamp((v - low) / (high - low), 0.0, 1.0) * 255.0 + 0.5);
}

}  // namespace

void WriteHeatMaps(const std::string& path, const HeatMaps& maps) {
  if (!(maps.high > maps.low)) throw std::invalid_argument("heat map: the scale's high must be above its low");
  if (maps.panels.empty()) throw std::invalid_argument("heat map: no panels");
  const int px = std::max(1, maps.pixels_per_cell);
  int width = kMargin, height = 0;
  for (const HeatPanel& p : maps.panels) {
    if (p.width <= 0 || p.height <= 0 || p.values.size() != static_cast<std::size_t>(p.width) * p.height) {
      throw std::invalid_argument("heat map: panel '" + p.title + "' has " + std::to_string(p.values.size()) +
                                  " values for " + std::to_string(p.width) + " x " + std::to_string(p.height) +
                                  " cells");
    }
    width += p.width * px + kMargin;
    height = std::max(height, p.height * px);
  }
  const int bar_top = kTitle + height + kMargin;
  cv::Mat image(bar_top + kBar + 2 * kMargin, width, CV_8UC3, cv::Scalar(255, 255, 255));
  int left = kMargin;
  for (const HeatPanel& p : maps.panels) {
    cv::Mat levels(p.height, p.width, CV_8UC1), nan(p.height, p.width, CV_8UC1);
    for (int j = 0; j < p.height; ++j) {
      for (int i = 0; i < p.width; ++i) {
        const double v = p.values[static_cast<std::size_t>(j) * p.width + i];
        const int row = p.height - 1 - j;  // the bottom row of the map at the bottom of the image
        levels.at<std::uint8_t>(row, i) = std::isnan(v) ? 0 : Level(v, maps.low, maps.high);
        nan.at<std::uint8_t>(row, i) = std::isnan(v) ? 255 : 0;
      }
    }
    cv::Mat coloured, big, big_nan;
    cv::applyColorMap(levels, coloured, cv::COLORMAP_VIRIDIS);
    coloured.setTo(cv::Scalar(0, 0, 0), nan);
    cv::resize(coloured, big, cv::Size(p.width * px, p.height * px), 0, 0, cv::INTER_NEAREST);
    big.copyTo(image(cv::Rect(left, kTitle, big.cols, big.rows)));
    Text(image, p.title, cv::Point(left, kTitle - 8));
    left += big.cols + kMargin;
  }
  // The colour bar, with its ends and middle labelled.
  const int bar_width = width - 2 * kMargin;
  cv::Mat ramp(1, 256, CV_8UC1);
  for (int k = 0; k < 256; ++k) ramp.at<std::uint8_t>(0, k) = static_cast<std::uint8_t>(k);
  cv::Mat ramp_coloured, bar;
  cv::applyColorMap(ramp, ramp_coloured, cv::COLORMAP_VIRIDIS);
  cv::resize(ramp_coloured, bar, cv::Size(bar_width, kBar), 0, 0, cv::INTER_LINEAR);
  bar.copyTo(image(cv::Rect(kMargin, bar_top, bar.cols, bar.rows)));
  char text[64];
  for (int k = 0; k <= 4; ++k) {
    const double v = maps.low + (maps.high - maps.low) * k / 4.0;
    std::snprintf(text, sizeof text, "%g %s", std::round(v * 10.0) / 10.0, maps.unit.c_str());
    Text(image, text, cv::Point(kMargin + bar_width * k / 4 - (k == 4 ? 60 : k == 0 ? 0 : 25), bar_top + kBar + 18));
  }
  try {
    if (!cv::imwrite(path, image)) throw std::runtime_error("");
  } catch (const std::exception&) {
    throw std::runtime_error("cannot write the heat map to " + path);
  }
}

}  // namespace multirobot_audio::tools
