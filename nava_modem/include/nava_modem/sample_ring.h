#pragma once

// The last samples heard, by their index since the first (a ring a power of two long), so that
// a receiver can go back over a packet once it has found both its ends. No ROS.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nava_modem/power_of_two.h"

namespace nava_modem {

class SampleRing {
 public:
  // Keeps at least `samples` samples; silence before the first.
  explicit SampleRing(double samples) : ring_(PowerOfTwoAtLeast(samples), 0.0f), mask_(ring_.size() - 1) {}

  void Push(float sample) {
    ring_[static_cast<std::size_t>(count_) & mask_] = sample;
    ++count_;
  }
  // Sample n, if still kept: older ones have been overwritten by the ones size() later, and
  // ones not heard yet read what was there (silence, or a sample size() earlier).
  float operator[](std::int64_t n) const { return ring_[static_cast<std::size_t>(n) & mask_]; }
  std::int64_t count() const { return count_; }  // samples heard
  std::size_t size() const { return ring_.size(); }

 private:
  std::vector<float> ring_;
  std::size_t mask_;
  std::int64_t count_ = 0;
};

}  // namespace nava_modem
