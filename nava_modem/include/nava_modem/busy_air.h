#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "nava_modem/packet_receiver.h"

namespace nava_modem {

// Busy air in which no frame was found: the thesis's ZERO_BYTE noise. The air is busy while
// the in-band power is at or above the carrier threshold; a stretch of busy air ends after
// `release_seconds` of quiet (and once no frame is being waited for), and is reported when it
// lasted at least `min_seconds` and no frame was found in it.
class BusyAir {
 public:
  BusyAir(double release_seconds, double min_seconds) : release_(release_seconds), min_(min_seconds) {}

  void SetThreshold(std::optional<double> db);
  void Reset() { busy_ = false; }
  // A step of audio ending at `time` (s): its in-band power (linear, full-scale tone = 1) and
  // a quality figure averaged into the report; `waiting`: a frame may still come out of it.
  void Step(double time, double power, double quality, bool waiting, std::vector<RxEvent>& events);
  // The receiver found a frame (a packet or noise of its own kind) in the busy air.
  void FrameFound() {
    if (busy_) had_frame_ = true;
  }
  bool busy() const { return busy_; }
  double last_loud() const { return last_loud_; }  // s: the busy stretch's last loud step

 private:
  double release_, min_;
  std::optional<double> threshold_power_;
  bool busy_ = false, had_frame_ = false;
  double start_ = 0.0, last_loud_ = 0.0, power_sum_ = 0.0, quality_sum_ = 0.0;
  std::int64_t steps_ = 0;
};

}  // namespace nava_modem
