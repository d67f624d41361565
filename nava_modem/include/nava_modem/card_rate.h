#pragma once

// A sound card's sample clock against the host's steady clock (NTP keeps that within a few ppm
// of true time): how many frames the card has captured by each moment, a line through them over
// the last minutes, its slope over the nominal rate. Ranging needs it: every two-way range is
// measured in the card's samples, so a card 100 ppm fast makes every range 100 ppm short. No ROS.
#include <cstdint>
#include <deque>

namespace nava_modem {

struct CardRateOptions {
  double nominal_rate = 48000.0;  // Hz
  double window = 120.0;          // s of the latest points the line is fitted over
  double min_span = 30.0;         // s the points must span before a rate is given
  // s of reads each point is the best of: the one whose count is furthest ahead, as a count read
  // late or in a sound server's chunks only ever lags the card (reads come every few ms)
  double spacing = 2.0;
  double max_error = 0.002;       // |rate error| beyond this is no card's: none is given
};

class CardRateTracker {
 public:
  // Throws std::invalid_argument for a rate, window, span or spacing not above 0, a span beyond
  // the window, or a max_error not in (0, 0.05].
  explicit CardRateTracker(const CardRateOptions& options);

  // By host time `seconds`, the card had captured `frames` since it opened (the frames read plus
  // those waiting in its buffer, so that when the reader runs late does not matter).
  void Add(double seconds, std::int64_t frames);
  // The card reopened (its frames count from 0 again), or its clock was moved on.
  void Reset() { points_.clear(); }
  // The card's rate over its nominal one, minus 1; NaN until the points span min_span (or when
  // the line says more than max_error).
  double rate_error() const;

 private:
  struct Point {
    double seconds;
    std::int64_t frames;
  };
  CardRateOptions options_;
  std::deque<Point> points_;
  double bin_start_ = 0.0;  // host s the newest point's reads began
};

}  // namespace nava_modem
