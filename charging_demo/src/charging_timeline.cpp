#include "charging_demo/charging_timeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace charging_demo {

namespace {

constexpr int kWidth = 1200, kLeft = 90, kRight = 20, kTop = 50, kBottom = 90, kLane = 46, kGap = 8;
const cv::Scalar kInk(40, 40, 40), kGrid(215, 215, 215);

// BGR per phase: calm for duty, warm for the lock and the charger.
cv::Scalar Colour(Phase phase) {
  switch (phase) {
    case Phase::kDuty: return {225, 235, 225};
    case Phase::kSeek: return {120, 200, 245};
    case Phase::kApproach: return {80, 170, 250};
    case Phase::kWait: return {60, 60, 230};
    case Phase::kDock: return {200, 120, 60};
    case Phase::kCharge: return {60, 170, 60};
    case Phase::kUndock: return {170, 120, 170};
  }
  return {0, 0, 0};
}

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.45) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, kInk, 1, cv::LINE_AA);
}

}  // namespace

void WriteChargingTimeline(const std::string& path, const ChargingTrialResult& trial,
                           double low_battery, const std::string& title) {
  const int robots = static_cast<int>(trial.robots.size());
  const int height = kTop + kBottom + robots * (kLane + kGap);
  cv::Mat image(height, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  const int plot_w = kWidth - kLeft - kRight;
  const double span = std::max(trial.duration, 1.0);
  auto x_of = [&](double t) { return kLeft + static_cast<int>(std::lround(plot_w * std::clamp(t / span, 0.0, 1.0))); };

  // Time axis: a grid line every 10, 15 or 30 minutes, whichever gives at most twelve.
  const double minutes = span / 60.0;
  double step = 10.0;
  for (double s : {10.0, 15.0, 30.0, 60.0, 120.0})
    if (minutes / s <= 12.0) { step = s; break; }
  const int plot_bottom = kTop + robots * (kLane + kGap);
  for (double m = 0.0; m <= minutes + 1e-9; m += step) {
    const int x = x_of(m * 60.0);
    cv::line(image, {x, kTop - 4}, {x, plot_bottom}, kGrid, 1);
    char label[16];
    std::snprintf(label, sizeof label, "%g", m);
    Text(image, label, {x - 8, plot_bottom + 18});
  }
  Text(image, "time (min)", {kLeft + plot_w / 2 - 30, plot_bottom + 38});

  for (int k = 0; k < robots; ++k) {
    const RobotRecord& r = trial.robots[k];
    const int top = kTop + k * (kLane + kGap), bottom = top + kLane;
    for (const PhaseSpan& p : r.phases)
      cv::rectangle(image, {x_of(p.start), top}, {std::max(x_of(p.end), x_of(p.start) + 1), bottom},
                    Colour(p.phase), cv::FILLED);
    cv::rectangle(image, {kLeft, top}, {kLeft + plot_w, bottom}, kGrid, 1);
    const int low_y = bottom - static_cast<int>(std::lround(low_battery * kLane));
    for (int x = kLeft; x < kLeft + plot_w; x += 12) cv::line(image, {x, low_y}, {x + 5, low_y}, kInk, 1);
    std::vector<cv::Point> battery;
    for (const auto& [t, level] : r.battery)
      battery.emplace_back(x_of(t), bottom - static_cast<int>(std::lround(level * kLane)));
    if (battery.size() >= 2) cv::polylines(image, battery, false, kInk, 1, cv::LINE_AA);
    char name[32];
    std::snprintf(name, sizeof name, "robot %d", k);
    Text(image, name, {8, top + kLane / 2 + 5});
  }

  const Phase phases[] = {Phase::kDuty, Phase::kSeek,   Phase::kApproach, Phase::kWait,
                          Phase::kDock, Phase::kCharge, Phase::kUndock};
  int x = kLeft;
  const int legend_y = plot_bottom + 62;
  for (Phase p : phases) {
    cv::rectangle(image, {x, legend_y - 11}, {x + 14, legend_y + 1}, Colour(p), cv::FILLED);
    Text(image, PhaseName(p), {x + 18, legend_y});
    x += 125;
  }
  Text(image, "line: battery", {x, legend_y});
  Text(image, title, {kLeft, 30}, 0.55);
  if (!cv::imwrite(path, image)) throw std::runtime_error(path + ": cannot write the timeline image");
}

}  // namespace charging_demo
