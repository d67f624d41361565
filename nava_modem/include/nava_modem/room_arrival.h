#pragma once

// When a `room` packet the receiver decoded first arrived (RxEvent::arrival, for ranging): the
// leading edge of its chirps' direct sound (first_arrival.h), read from the samples heard around
// them. No ROS.
#include <optional>
#include <vector>

#include "nava_modem/first_arrival.h"
#include "nava_modem/sample_ring.h"

namespace nava_modem {

class RoomArrival {
 public:
  // `chirp`: the chirp as sent.
  RoomArrival(const std::vector<float>& chirp, double sample_rate);

  // Seconds since the first sample heard at which the packet whose chirps start at samples `pre`
  // and `post` (as the decode placed them, to a fraction of a sample) first arrived: both chirps'
  // responses together (the direct sound 3 dB further over the noise than in one), or the
  // first's alone without `post` (a second chirp placed by the data, not heard above the room).
  double Time(const SampleRing& heard, double pre, std::optional<double> post);

 private:
  double sample_rate_;
  ArrivalTimer timer_;
};

}  // namespace nava_modem
