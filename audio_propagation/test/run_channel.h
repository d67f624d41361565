#pragma once

// Runs a simulated channel in the 50 ms steps a node or runner would, gathering its events; and
// the loud source the channel's tests use.
#include <algorithm>
#include <utility>

#include "audio_propagation/audio_channel.h"

namespace audio_propagation::test {

// Source 60 dB at 1 m, threshold 30 dB: heard up to 31.6 m in the open.
inline PropagationOptions Loud() {
  PropagationOptions o;
  o.source_level_db = 60.0;
  o.threshold_db = 30.0;
  o.threads = 1;
  return o;
}

inline AudioChannel::Events RunFor(AudioChannel& channel, double seconds) {
  AudioChannel::Events all;
  const double end = channel.time() + seconds;
  while (channel.time() < end - 1e-9) {
    auto e = channel.AdvanceTo(std::min(end, channel.time() + 0.05));
    for (auto& s : e.started) all.started.push_back(std::move(s));
    for (auto& r : e.received) all.received.push_back(std::move(r));
  }
  return all;
}

}  // namespace audio_propagation::test
