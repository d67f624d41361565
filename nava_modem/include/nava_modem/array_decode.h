#pragma once

#include <vector>

#include "nava_modem/direction_estimator.h"
#include "nava_modem/modem_profile.h"

namespace nava_modem {

// The direction estimator's settings for a profile: its band, and how much of each reception to
// use. nava: the whole packet, since it opens with a steady MARK tone (one frequency: its
// correlation repeats every 0.43 ms) and only the data bits' two tones pin the delay down. room:
// its first chirp, 0.12 s sweeping 600-5400 Hz, whose direct sound the reverberation has not yet
// caught up with.
DirectionOptions DirectionOptionsFor(Profile profile, const ModemOptions& modem, std::vector<Microphone2D> mics);

// The channel a recording is decoded on: the loudest, the microphone nearest the sender or least
// shadowed. Not the sum: the microphones hear the sound at different delays, and with spacings of
// a few centimetres their sum comb-filters the modem's upper tones.
std::size_t LoudestChannel(const std::vector<std::vector<float>>& channels);

// A whole multi-channel recording decoded: the profile's receiver on the loudest channel, and each
// event's direction from that event's own samples on every channel (when there are two or more
// microphones). `estimate_seconds`, if given, gets the CPU time spent in
// the direction estimator (to compare with the decoding's).
std::vector<RxEvent> DecodeArray(const ModemProfile& profile, const ReceiverOptions& options,
                                 const std::vector<std::vector<float>>& channels, const std::vector<Microphone2D>& mics,
                                 double* estimate_seconds = nullptr);

}  // namespace nava_modem
