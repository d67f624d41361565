#pragma once

// A decode table for tests that need a model but not the receiver's measurements: one cell per
// kind, every packet decoded with the same probability, nava's band and whine.
#include <string>

#include "audio_propagation/decode_table.h"

namespace audio_propagation::test {

inline DecodeTable FlatTable(const std::string& profile, double delivered = 0.5) {
  DecodeTable t;
  t.profile = profile;
  t.packets = 1;
  t.whine_hz = 3000.0;
  t.band_low_hz = 2150.0;
  t.band_high_hz = 3850.0;
  t.snr_db = {0.0};
  t.drr_db = {0.0};
  t.rt60 = {0.5};
  t.Resize();
  for (DecodeOutcome& o : t.cells) o.packet = delivered;
  return t;
}

}  // namespace audio_propagation::test
