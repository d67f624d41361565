#include "tool_args/line_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace multirobot_audio::tools {
namespace {

constexpr int kWidth = 900, kHeight = 560;
constexpr int kLeft = 80, kRight = 250, kTop = 64, kBottom = 70;
const cv::Scalar kInk(40, 40, 40), kGrid(225, 225, 225);
const cv::Scalar kPalette[] = {{180, 119, 31}, {14, 127, 255}, {44, 160, 44}, {40, 39, 214}, {189, 103, 148}, {75, 86, 140}};

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.5) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, kInk, 1, cv::LINE_AA);
}

// A segment drawn in the series' style: dashes and dots are pieces of it.
void Segment(cv::Mat& image, cv::Point2d a, cv::Point2d b, const cv::Scalar& colour, LineSeries::Style style) {
  if (style == LineSeries::Style::kSolid) {
    cv::line(image, a, b, colour, 2, cv::LINE_AA);
    return;
  }
  const double on = style == LineSeries::Style::kDashed ? 10.0 : 3.0, period = style == LineSeries::Style::kDashed ? 16.0 : 8.0;
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  for (double s = 0.0; s < length; s += period) {
    const double e = std::min(length, s + on);
    cv::line(image, a + (b - a) * (s / length), a + (b - a) * (e / length), colour, 2, cv::LINE_AA);
  }
}

}  // namespace

void WriteLineChart(const std::string& path, const LineChart& chart) {
  cv::Mat image(kHeight, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  double x_min = 1e300, x_max = -1e300;
  for (const LineSeries& s : chart.series) {
    for (double x : s.x) {
      x_min = std::min(x_min, x);
      x_max = std::max(x_max, x);
    }
  }
  if (!(x_max > x_min)) {
    x_min -= 1.0;
    x_max += 1.0;
  }
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  auto px = [&](double x, double y) {
    const double yc = std::clamp(y, chart.y_min, chart.y_max);
    return cv::Point2d(kLeft + (x - x_min) / (x_max - x_min) * plot_w,
                       kTop + (chart.y_max - yc) / (chart.y_max - chart.y_min) * plot_h);
  };
  char label[64];
  for (int k = 0; k <= 5; ++k) {
    const double y = chart.y_min + k * (chart.y_max - chart.y_min) / 5.0;
    cv::line(image, px(x_min, y), px(x_max, y), kGrid, 1);
    std::snprintf(label, sizeof label, "%g", y);
    Text(image, label, px(x_min, y) + cv::Point2d(-45, 5));
  }
  // The x ticks: the first series' own x values when they are few, else eight even steps.
  std::vector<double> ticks;
  if (!chart.series.empty() && chart.series[0].x.size() <= 12) {
    ticks = chart.series[0].x;
  } else {
    for (int k = 0; k <= 8; ++k) ticks.push_back(x_min + k * (x_max - x_min) / 8.0);
  }
  for (double x : ticks) {
    cv::line(image, px(x, chart.y_min), px(x, chart.y_max), kGrid, 1);
    std::snprintf(label, sizeof label, "%g", std::round(x * 10.0) / 10.0);
    Text(image, label, px(x, chart.y_min) + cv::Point2d(-10, 20));
  }
  cv::rectangle(image, px(x_min, chart.y_max), px(x_max, chart.y_min), kInk, 1);
  Text(image, chart.title, {kLeft, 26}, 0.65);
  Text(image, chart.x_label, {kLeft + static_cast<int>(plot_w / 2) - 60, kHeight - 20});
  Text(image, chart.y_label, {10, kTop - 12});
  int legend_y = kTop + 10;
  for (const LineSeries& s : chart.series) {
    const cv::Scalar colour = kPalette[static_cast<std::size_t>(s.colour) % std::size(kPalette)];
    for (std::size_t k = 0; k + 1 < s.x.size(); ++k) Segment(image, px(s.x[k], s.y[k]), px(s.x[k + 1], s.y[k + 1]), colour, s.style);
    for (std::size_t k = 0; k < s.x.size(); ++k) cv::circle(image, px(s.x[k], s.y[k]), 3, colour, cv::FILLED, cv::LINE_AA);
    Segment(image, {kWidth - kRight + 15.0, legend_y - 4.0}, {kWidth - kRight + 55.0, legend_y - 4.0}, colour, s.style);
    Text(image, s.label, {kWidth - kRight + 62, legend_y}, 0.45);
    legend_y += 22;
  }
  if (!cv::imwrite(path, image)) throw std::runtime_error(path + ": cannot write the PNG");
}

}  // namespace multirobot_audio::tools
