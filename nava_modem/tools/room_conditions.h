#pragma once

// The room conditions nava_bench --rooms measures each profile under (the rows of its table).
// Each is what a robot's microphone hears in a building: reverberation louder than the direct
// sound, speech, a motor's whine, a speaker whose response tilts, a sender's clock that is off.
// Every row also has a faint white-noise floor (SNR 40 dB) unless it sets a noise of its own.
#include <string>
#include <vector>

#include "nava_modem/room_channel.h"

namespace nava_modem::tools {

struct RoomCondition {
  std::string name;
  RoomOptions room;
  bool speech = false;  // an espeak-ng speech recording as the interferer, at room.sir_db
};

inline std::vector<RoomCondition> RoomConditions() {
  auto base = [] {
    RoomOptions o;
    o.noise = RoomOptions::Noise::kWhite;
    o.snr_db = 40.0;
    return o;
  };
  std::vector<RoomCondition> rows;
  auto add = [&](const std::string& name, auto change, bool speech = false) {
    RoomCondition c{name, base(), speech};
    change(c.room);
    rows.push_back(c);
  };
  add("rt60 0.3 s, drr +3 dB", [](RoomOptions& o) { o.rt60 = 0.3; o.drr_db = 3.0; });
  add("rt60 0.6 s, drr -6 dB", [](RoomOptions& o) { o.rt60 = 0.6; o.drr_db = -6.0; });
  add("rt60 1.0 s, drr -10 dB", [](RoomOptions& o) { o.rt60 = 1.0; o.drr_db = -10.0; });
  add("speech, sir 0 dB", [](RoomOptions& o) { o.sir_db = 0.0; }, true);
  add("speech, sir -6 dB", [](RoomOptions& o) { o.sir_db = -6.0; }, true);
  add("whine 2500 Hz, sir -6 dB", [](RoomOptions& o) { o.whine_hz = 2500.0; o.whine_sir_db = -6.0; });
  add("tilt -15 dB", [](RoomOptions& o) { o.tilt_db = -15.0; });
  add("tilt +10 dB", [](RoomOptions& o) { o.tilt_db = 10.0; });
  add("clock +1 %", [](RoomOptions& o) { o.clock_offset = 0.01; });
  add("clock -1 %", [](RoomOptions& o) { o.clock_offset = -0.01; });
  add("office at 4 m", [](RoomOptions& o) {
    o.rt60 = 0.5; o.drr_db = -8.0; o.noise = RoomOptions::Noise::kPink; o.snr_db = 6.0; o.clock_offset = 0.003;
  });
  add("all at once", [](RoomOptions& o) {
    o.rt60 = 0.5; o.drr_db = 0.0; o.sir_db = 3.0; o.snr_db = 3.0; o.tilt_db = -6.0; o.clock_offset = -0.005;
  }, true);
  return rows;
}

// A tilt runs across the profile's own band: between the nava tones (so that "-15 dB" makes
// SPACE 15 dB weaker than MARK), across 600-5400 Hz for room.
inline void TiltOverBand(RoomOptions& o, bool nava, const ModemOptions& modem) {
  o.tilt_low_hz = nava ? std::min(modem.mark_hz, modem.space_hz) : 600.0;
  o.tilt_high_hz = nava ? std::max(modem.mark_hz, modem.space_hz) : 5400.0;
}

}  // namespace nava_modem::tools
