#pragma once

// Where a lone `room` chirp's partner lies, by the data after it. In a room whose reverberation
// stands 15 dB or more over the direct sound for seconds, a packet's second chirp gives a
// matched-filter peak that is one among many as tall, and no chirp search finds it; the 42
// symbols between the chirps still say where the sender put them. No ROS.
#include <cstddef>
#include <vector>

#include "nava_modem/room_symbol_reader.h"
#include "nava_modem/sample_ring.h"

namespace nava_modem {

// The trials' step (s): a distance found is within half of it of the best trial's, so the
// caller lines the chirps' envelopes up within this.
constexpr double kDataSearchStepS = 0.002;

// Distances (samples) from a first chirp at sample `pre` at which its second chirp may start,
// best first, at most 2: the symbols are read at trial distances kDataSearchStepS apart from
// `shortest` to `longest` (`nominal` at our clock), skipping those whose second chirp has not
// been heard to its end, and scored by how they stand out in their sub-bands (HopContrast),
// every second symbol first and the best three trials at least 10 ms apart again on all 42.
// Empty when no trial scores as a packet (a lone chirp in noise, or speech that passed for one).
// `chirp_length`: samples.
std::vector<double> SearchByData(RoomSymbolReader& symbols, const SampleRing& heard, double pre, double nominal, double shortest,
                                 double longest, std::size_t chirp_length);

}  // namespace nava_modem
