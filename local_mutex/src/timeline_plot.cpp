#include "local_mutex/timeline_plot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace local_mutex {
namespace {

const cv::Scalar kInk(30, 30, 30), kGrid(225, 225, 225), kSent(40, 90, 200), kHeard(60, 140, 40),
    kNoise(30, 30, 200), kHeld(20, 20, 20), kWanted(80, 80, 80);
constexpr int kLeft = 90, kRight = 30, kTop = 50, kBottom = 50, kLane = 150, kWidth = 1800;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

void Text(cv::Mat& img, const std::string& s, cv::Point at, double scale, const cv::Scalar& colour,
          int thickness = 1) {
  cv::putText(img, s, at, kFont, scale, colour, thickness, cv::LINE_AA);
}

void Dashed(cv::Mat& img, int x0, int x1, int y, const cv::Scalar& colour) {
  for (int x = x0; x < x1; x += 12) cv::line(img, {x, y}, {std::min(x + 6, x1), y}, colour, 2, cv::LINE_AA);
}

}  // namespace

void DrawTimeline(const TeamSim& sim, const std::string& path) {
  const std::vector<RobotEvent>& events = sim.events();
  if (events.empty()) throw std::runtime_error("timeline: the run has no recorded events (record was off?)");
  const double end = std::max(10.0, std::ceil(sim.time() / 10.0) * 10.0);
  const int height = kTop + kBottom + kLane * static_cast<int>(sim.size());
  cv::Mat img(height, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  const double px_per_s = (kWidth - kLeft - kRight) / end;
  auto X = [&](double t) { return kLeft + static_cast<int>(std::lround(t * px_per_s)); };
  auto Y = [&](std::size_t robot) { return kTop + kLane * static_cast<int>(robot) + kLane / 2 + 10; };

  // Time grid every 10 s.
  for (double t = 0.0; t <= end + 1e-9; t += 10.0) {
    cv::line(img, {X(t), kTop}, {X(t), height - kBottom}, kGrid, 1);
    Text(img, std::to_string(static_cast<int>(t)), {X(t) - 8, height - kBottom + 20}, 0.45, kInk);
  }
  Text(img, "time (s)", {kWidth / 2 - 30, height - 10}, 0.5, kInk);
  Text(img, "local mutex: thin WANTED, thick HELD, dashed SILENT; v sent (type, T, id), ^ heard, x noise; [clock]",
       {kLeft, 25}, 0.5, kInk);

  for (std::size_t r = 0; r < sim.size(); ++r) {
    Text(img, "#" + std::to_string(sim.robot(r).id), {10, Y(r) + 6}, 0.6, kInk, 2);
    // State segments from the state changes.
    State state = State::kReleased;
    double since = 0.0;
    auto segment = [&](double until) {
      const int x0 = X(since), x1 = X(until);
      switch (state) {
        case State::kWanted:
          cv::line(img, {x0, Y(r)}, {x1, Y(r)}, kWanted, 2, cv::LINE_AA);
          break;
        case State::kHeld:
          cv::line(img, {x0, Y(r)}, {x1, Y(r)}, kHeld, 9);
          break;
        case State::kSilent:
          Dashed(img, x0, x1, Y(r), kWanted);
          break;
        case State::kReleased:
          cv::line(img, {x0, Y(r)}, {x1, Y(r)}, kGrid, 1);
          break;
      }
    };
    for (const RobotEvent& e : events) {
      if (e.robot != r || e.event.kind != MutexEvent::Kind::kStateChange) continue;
      segment(e.event.time);
      state = e.event.state;
      since = e.event.time;
    }
    segment(sim.time());
  }

  // Messages, alternating label heights so neighbours do not overwrite each other.
  std::vector<int> sent_count(sim.size(), 0), heard_count(sim.size(), 0);
  for (const RobotEvent& e : events) {
    const int x = X(e.event.time), y = Y(e.robot);
    const std::string clock = "[" + std::to_string(e.event.clock) + "]";
    switch (e.event.kind) {
      case MutexEvent::Kind::kSent: {
        const int lift = 18 + 16 * (sent_count[e.robot]++ % 2);
        cv::arrowedLine(img, {x, y - 45}, {x, y - 6}, kSent, 2, cv::LINE_AA, 0, 0.25);
        Text(img, Describe(e.event.message), {x - 30, y - 45 - lift + 14}, 0.4, kSent);
        Text(img, clock, {x + 4, y - 20}, 0.38, kSent);
        break;
      }
      case MutexEvent::Kind::kHeard: {
        const int drop = 16 * (heard_count[e.robot]++ % 2);
        cv::arrowedLine(img, {x, y + 40}, {x, y + 6}, kHeard, 1, cv::LINE_AA, 0, 0.25);
        Text(img, clock, {x - 10, y + 54 + drop}, 0.38, kHeard);
        break;
      }
      case MutexEvent::Kind::kNoise:
      case MutexEvent::Kind::kMalformed:
      case MutexEvent::Kind::kDuplicateId:
        cv::drawMarker(img, {x, y + 20}, kNoise, cv::MARKER_TILTED_CROSS, 10, 2);
        Text(img, clock, {x - 10, y + 54}, 0.38, kNoise);
        break;
      case MutexEvent::Kind::kStateChange:
      case MutexEvent::Kind::kEcho:
        break;
    }
  }
  if (!cv::imwrite(path, img)) throw std::runtime_error("timeline: cannot write " + path);
}

}  // namespace local_mutex
