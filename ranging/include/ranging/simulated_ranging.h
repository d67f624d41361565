#pragma once

// Two-way ranging as a simulated team measures it: the same TwoWayRanger a real robot runs, fed
// the timings a real team would share. Each robot's sound card has a clock of its own (an offset
// and a rate within +-100 ppm of true time); every packet a robot sends is timed by its own
// microphone, and every packet a robot decodes is timed at its true arrival (the sender's start
// plus the path's length over the speed of sound) with an error drawn from what the real
// receiver shows through measured rooms (ArrivalErrors). A range therefore exists only after
// an exchange both ways, carries the real one's errors, and drifts like it where the clocks
// do. Each robot learns its own card's rate some 30 s after it starts, to a few ppm, as
// nava_modem's CardRateTracker does against the host's clock. No ROS.
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "ranging/two_way_ranger.h"

namespace ranging {

// How far a receiver's first-arrival timing lands from the truth: signed errors (s) at evenly
// spaced probabilities 0, 1/(n-1), ..., 1, ascending, from the real receiver run through
// measured rooms (nava_bench --arrival --errors-out). A draw interpolates between them.
struct ArrivalErrors {
  std::vector<double> quantiles;
  double Draw(std::mt19937& rng) const;
};

// Throws std::invalid_argument naming the problem: fewer than 2 quantiles, one not finite or
// beyond 1 s, or not ascending.
void ValidateArrivalErrors(const ArrivalErrors& errors);

struct SimulatedRangingOptions {
  RangerOptions ranger;
  ArrivalErrors errors;             // every timing's (a robot's own packets' too)
  double max_clock_rate_error = 100e-6;  // each sound card's rate against true time, drawn in +-
  // What a listener's receiver reports of the sender's clock rate (Timing::rate_error): the true
  // ratio plus this much noise (one standard deviation); below 0: nothing (0 is reported, as
  // nava's receiver does: its bit clock is not trusted).
  double rate_report_std = -1.0;
  std::uint32_t seed = 1;
};

// Throws std::invalid_argument naming the field: the ranger's options, the errors, a clock rate
// error not in 0..0.001, a rate_report_std above 0.001.
void ValidateSimulatedRangingOptions(const SimulatedRangingOptions& options);

class SimulatedRanging {
 public:
  // `robots` in the order every index here refers to. Throws std::invalid_argument for
  // impossible options, no robots or an empty name.
  SimulatedRanging(std::vector<std::string> robots, const SimulatedRangingOptions& options);

  // `sender` started sending `data` at true time `start` (s): its own microphone times it.
  void Sent(std::size_t sender, const std::vector<std::uint8_t>& data, double start);
  // `listener` decoded `sender`'s packet carrying `data`, which travelled `path_length` m; the
  // sending is the latest of that payload by that sender not after `heard_at` (true s). False,
  // and nothing timed, when no such sending is known.
  bool Heard(std::size_t listener, std::size_t sender, const std::vector<std::uint8_t>& data, double path_length,
             double heard_at);

  // What `robot` knows of `teammate`'s range at true time `now`.
  std::optional<Range> RangeTo(std::size_t robot, std::size_t teammate, double now) const;
  std::vector<Range> Ranges(std::size_t robot, double now) const;
  // `robot`'s sound-card clock at true time t.
  double Clock(std::size_t robot, double t) const;
  double clock_rate_error(std::size_t robot) const { return clocks_.at(robot).rate_error; }
  // Every robot's refusals summed (none in a healthy run).
  Refused refused() const;
  std::size_t size() const { return robots_.size(); }

 private:
  struct SoundCard {
    double rate_error, offset;
    double first_seen = std::numeric_limits<double>::quiet_NaN();  // true s its robot first sent or heard
    bool rate_known = false;  // its robot has learnt its rate (as nava_modem's CardRateTracker)
  };
  void TrackCardRate(std::size_t robot, double t);
  struct Sending {
    std::size_t sender;
    std::vector<std::uint8_t> data;
    double start;
    Timing own;  // the sender's own timing of it
  };

  std::vector<std::string> robots_;
  SimulatedRangingOptions options_;
  std::vector<SoundCard> clocks_;
  std::vector<TwoWayRanger> rangers_;
  std::deque<Sending> sendings_;  // the latest, newest last
  std::mt19937 rng_;
};

}  // namespace ranging
