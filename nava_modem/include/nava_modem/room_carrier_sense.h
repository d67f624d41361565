#pragma once

// The `room` receiver's carrier sense: the in-band level (the profile's band, smoothed over
// 10 ms) for the link's level_db, stepped every millisecond into busy air (BusyAir) for ZERO_BYTE
// reports of busy air in which no chirp was heard. No ROS.
#include <cstdint>
#include <optional>
#include <vector>

#include "nava_modem/band_level.h"
#include "nava_modem/busy_air.h"

namespace nava_modem {

class RoomCarrierSense {
 public:
  explicit RoomCarrierSense(double sample_rate);

  // Feeds one sample; true when a busy-air Step is due (every millisecond).
  bool Push(float sample) {
    level_.Push(sample);
    if (++count_ < step_) return false;
    count_ = 0;
    return true;
  }
  // The step ending at `time` (s); `waiting`: a chirp may still come out of the busy air.
  void Step(double time, bool waiting, std::vector<RxEvent>& events) { busy_.Step(time, level_.power(), 0.0, waiting, events); }
  // When the busy stretch heard last ends (s) unless more comes: busy air ends after a
  // symbol's time of quiet.
  double quiet_from() const;
  void SetThreshold(std::optional<double> db) { busy_.SetThreshold(db); }
  void Reset() { busy_.Reset(); }
  void FrameFound() { busy_.FrameFound(); }
  double level_db() const { return level_.db(); }

 private:
  BandLevel level_;
  BusyAir busy_;
  std::int64_t step_, count_ = 0;
};

}  // namespace nava_modem
