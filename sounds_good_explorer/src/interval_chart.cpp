#include "sounds_good_explorer/interval_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace sounds_good_explorer {

namespace {

constexpr int kWidth = 1000, kHeight = 560;
constexpr int kLeft = 90, kRight = 20, kTop = 50, kBottom = 80;
const cv::Scalar kInk(40, 40, 40), kGrid(225, 225, 225);

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.5,
          bool centred = false) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  if (centred) at.x -= size.width / 2;
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, kInk, 1, cv::LINE_AA);
}

// A round step for the y axis giving about five grid lines.
double NiceStep(double span) {
  const double raw = span / 5.0;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double f : {1.0, 2.0, 5.0})
    if (raw <= f * magnitude) return f * magnitude;
  return 10.0 * magnitude;
}

}  // namespace

void WriteIntervalChart(const std::string& path, const IntervalChart& chart) {
  cv::Mat image(kHeight, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  double top = 0.0;
  for (const IntervalSeries& s : chart.series)
    for (std::size_t i = 0; i < s.mean.size(); ++i)
      if (std::isfinite(s.mean[i]))
        top = std::max(top, s.mean[i] + (i < s.half_width.size() && std::isfinite(s.half_width[i])
                                              ? s.half_width[i] : 0.0));
  if (top <= 0.0) top = 1.0;
  const double step = NiceStep(top);
  top = std::ceil(top / step) * step;
  const int plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  auto y_of = [&](double v) { return kTop + static_cast<int>(std::lround(plot_h * (1.0 - v / top))); };

  for (double v = 0.0; v <= top + step * 1e-6; v += step) {
    cv::line(image, {kLeft, y_of(v)}, {kLeft + plot_w, y_of(v)}, kGrid, 1);
    char label[32];
    std::snprintf(label, sizeof label, "%g", v);
    Text(image, label, {kLeft - 60, y_of(v) + 5}, 0.45);
  }
  cv::rectangle(image, {kLeft, kTop}, {kLeft + plot_w, kTop + plot_h}, kInk, 1);
  const int slots = std::max<int>(1, static_cast<int>(chart.x_ticks.size()));
  const double slot = static_cast<double>(plot_w) / slots;
  const int count = static_cast<int>(chart.series.size());
  for (int x = 0; x < slots; ++x) {
    const int centre = kLeft + static_cast<int>((x + 0.5) * slot);
    if (x < static_cast<int>(chart.x_ticks.size()))
      Text(image, chart.x_ticks[x], {centre, kTop + plot_h + 20}, 0.42, true);
    for (int k = 0; k < count; ++k) {
      const IntervalSeries& s = chart.series[k];
      if (x >= static_cast<int>(s.mean.size()) || !std::isfinite(s.mean[x])) continue;
      const int px = centre + static_cast<int>((k - (count - 1) / 2.0) * slot * 0.6 / std::max(count, 1));
      const cv::Scalar colour(s.rgb[2], s.rgb[1], s.rgb[0]);
      const double half = x < static_cast<int>(s.half_width.size()) && std::isfinite(s.half_width[x])
                              ? s.half_width[x] : 0.0;
      const int lo = y_of(std::max(0.0, s.mean[x] - half)), hi = y_of(s.mean[x] + half);
      cv::line(image, {px, lo}, {px, hi}, colour, 2, cv::LINE_AA);
      cv::line(image, {px - 4, lo}, {px + 4, lo}, colour, 2, cv::LINE_AA);
      cv::line(image, {px - 4, hi}, {px + 4, hi}, colour, 2, cv::LINE_AA);
      cv::circle(image, {px, y_of(s.mean[x])}, 4, colour, cv::FILLED, cv::LINE_AA);
    }
  }
  Text(image, chart.title, {kWidth / 2, 30}, 0.6, true);
  Text(image, chart.x_label, {kLeft + plot_w / 2, kHeight - 25}, 0.5, true);
  // The y label goes above the axis: OpenCV writes no rotated text.
  Text(image, chart.y_label, {10, kTop - 12}, 0.45);
  for (int k = 0; k < count; ++k) {
    const IntervalSeries& s = chart.series[k];
    const cv::Point at(kLeft + 10 + 170 * k, kHeight - 8);
    cv::circle(image, at + cv::Point(0, -5), 5, cv::Scalar(s.rgb[2], s.rgb[1], s.rgb[0]), cv::FILLED);
    Text(image, s.name, at + cv::Point(10, 0), 0.45);
  }
  bool written = false;
  try {
    written = cv::imwrite(path, image);
  } catch (const cv::Exception&) {
    written = false;
  }
  if (!written) throw std::runtime_error(path + ": cannot write the chart (PNG)");
}

}  // namespace sounds_good_explorer
