#pragma once

// The part of a packet's sound that its first arrival is timed on (first_arrival.h), the same
// for a packet heard from a teammate and for one's own, so that whatever the choice does to the
// timing is the same on both sides of a two-way range. No ROS.
#include <cstdint>
#include <vector>

#include "nava_modem/modem_options.h"
#include "nava_modem/modem_profile.h"

namespace nava_modem {

struct TimingReference {
  std::vector<float> sound;
  double offset = 0.0;  // samples from the packet's first to the reference's first
};

// The same for every packet of a profile, so that a receiver prepares its timing once. room: the
// packet's first chirp, made for timing. nava: bits kFirstTimedBit to kEndTimedBit, the end of the
// SPACE lead, the break (the one step nothing else in the packet repeats: the header byte
// alternates, and a reference of it alone matches two bits early as well), the header byte and
// the next start bit: no data. Its phase need not be the packet's: a constant phase turns the
// analytic response, not its envelope.
TimingReference PacketTimingReference(Profile profile, const ModemOptions& options);
constexpr int kFirstTimedBit = 12, kEndTimedBit = 51;

}  // namespace nava_modem
