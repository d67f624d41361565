#pragma once

// Test-only helpers for a profile end to end: its receiver fed as a sound card feeds it, the
// packets it decoded, and a sender whose clock is off.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "nava_modem/modem_profile.h"
#include "nava_modem/room_channel.h"

namespace nava_modem::test_signals {

// Every event the profile's receiver reports of `audio`, fed in pieces of 441 samples as a sound
// card delivers it, then flushed.
inline std::vector<RxEvent> Hear(const ModemProfile& profile, const std::vector<float>& audio) {
  auto rx = profile.MakeReceiver({});
  std::vector<RxEvent> events;
  for (std::size_t at = 0; at < audio.size(); at += 441) rx->Process(audio.data() + at, std::min<std::size_t>(441, audio.size() - at), events);
  rx->Flush(events);
  return events;
}

// The data of the packets (frames) among `events`, in order.
inline std::vector<std::vector<std::uint8_t>> PacketsOf(const std::vector<RxEvent>& events) {
  std::vector<std::vector<std::uint8_t>> out;
  for (const RxEvent& e : events) {
    if (e.kind == RxEvent::Kind::kPacket) out.push_back(e.data);
  }
  return out;
}

// The sender's clock off by `offset` (+0.01: 1 % fast): linear interpolation is enough for a
// test at these rates (the tones are far below Nyquist).
inline std::vector<float> ClockOffset(const std::vector<float>& in, double offset) {
  std::vector<float> out;
  for (double t = 0.0; t + 1.0 < in.size(); t += 1.0 + offset) {
    const std::size_t k = static_cast<std::size_t>(t);
    const double f = t - k;
    out.push_back(static_cast<float>((1.0 - f) * in[k] + f * in[k + 1]));
  }
  return out;
}

// "An office at 4 m" and a motor: RT60 0.5 s, DRR -8 dB, pink noise at 6 dB, the sender's clock
// 0.3 % fast, a whine as loud as the sound at 2500 Hz, the speaker's highs 10 dB down.
inline RoomOptions NoisyOffice() {
  RoomOptions office;
  office.rt60 = 0.5;
  office.drr_db = -8.0;
  office.noise = RoomOptions::Noise::kPink;
  office.snr_db = 6.0;
  office.clock_offset = 0.003;
  office.whine_hz = 2500.0;
  office.whine_sir_db = 0.0;
  office.tilt_db = -10.0;
  office.tilt_low_hz = 600.0;
  office.tilt_high_hz = 5400.0;
  return office;
}

}  // namespace nava_modem::test_signals
