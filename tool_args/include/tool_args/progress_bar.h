#pragma once
// A progress line for batch tools: one line on stderr, redrawn in place, with a bar, the count
// and an estimate of the time left.
#include <chrono>
#include <cstdio>
#include <string>

namespace multirobot_audio::tools {

class ProgressBar {
 public:
  explicit ProgressBar(std::string unit = "trials")
      : unit_(std::move(unit)), start_(std::chrono::steady_clock::now()) {}
  void operator()(int done, int total) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int width = 40, filled = width * done / total;
    const double left = done > 0 ? elapsed * (total - done) / done : 0.0;
    std::fprintf(stderr, "\r[%s%s] %d/%d %s, %.0f s elapsed, ~%.0f s left ",
                 std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(), done,
                 total, unit_.c_str(), elapsed, left);
    if (done == total) std::fprintf(stderr, "\n");
  }

 private:
  std::string unit_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace multirobot_audio::tools
