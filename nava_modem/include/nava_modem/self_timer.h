#pragma once

// A link's own packets as its own microphone hears them: the first arrival of each, on the same
// capture clock as the packets it receives (first_arrival.h), looked for over the whole of the
// longest loop until one is found, then around the loop's delay (and over the whole loop again
// when the sound is not just where that delay puts it). Two-way ranging (ranging/) needs
// both: the sound card's playback and capture latencies are unknown, but timing one's own sound
// on the capture clock takes them out. No ROS.
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "nava_modem/first_arrival.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/timing_reference.h"

namespace nava_modem {

struct OwnTiming {
  std::vector<std::uint8_t> data;  // the packet's 4 data bytes
  double arrival = 0.0;            // s on the receiver's clock; NaN when the microphone did not hear it
};

class SelfTimer {
 public:
  // `max_loop` (s): the longest the sound may take from being handed to playback to being
  // captured (both buffers and the sound server's); the sound is looked for that long after it
  // was sent. Throws std::invalid_argument for a loop not above 0 or beyond 10 s.
  SelfTimer(const ModemProfile& profile, double max_loop);

  // A packet whose first sample was handed to playback when the receiver's clock read `sent` (s).
  void Sent(std::vector<std::uint8_t> data, double sent);
  // The microphone's samples, in order, from the receiver's clock `time()` on; appends the own
  // packets whose search window has now been heard.
  void Heard(const float* samples, std::size_t count, std::vector<OwnTiming>& out);
  // The clock moved on without audio (the receiver flushed `seconds` of silence after a device
  // failure): the pending packets are reported unheard, the ring holds silence.
  void Skip(double seconds, std::vector<OwnTiming>& out);
  double time() const { return static_cast<double>(n_) / rate_; }
  std::size_t pending() const { return pending_.size(); }

 private:
  struct Pending {
    std::vector<std::uint8_t> data;
    double sent;            // s, the receiver's clock when it was sent
    bool narrow;            // searched around the last loop's delay
    std::int64_t from, to;  // the samples to search, [from, to)
  };
  void Judge(std::vector<OwnTiming>& out);

  double rate_;
  double max_loop_;
  TimingReference reference_;
  ArrivalTimer wide_, narrow_;  // over the whole of max_loop, and around the last loop's delay
  std::optional<double> loop_;  // s from sending to hearing, as last timed
  std::vector<float> heard_;  // scratch
  std::vector<float> ring_;
  std::size_t mask_;
  std::int64_t n_ = 0;  // samples heard
  std::deque<Pending> pending_;
};

}  // namespace nava_modem
