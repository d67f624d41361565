#pragma once

// The `room` profile receiver's soft decisions: from a packet's tone energies to the coded bits'
// log-likelihoods the Viterbi decoder takes. No ROS.
#include <vector>

#include "nava_modem/room_code.h"

namespace nava_modem {

// Each tone is judged against its own noise floor: its median over the packet's symbols that did
// not use its sub-band, scaled by how loud the symbol's time was across the other sub-bands.
// That takes out a whine, the speaker's tilt and the reverberant tails of earlier symbols, and
// discounts speech, which comes and goes. A tone's evidence is log(1 + energy / floor), so that
// one burst or click in a wrong tone cannot outvote the other symbols; a bit's soft decision is
// the best evidence among the tones that say 1 less the best among those that say 0 (max-log).
// `energy`: `symbols` rows of kBins tone energies (RoomSymbolReader) of one block (today's
// packet, a long frame's header or payload), whose symbols sound `tones` sub-bands at once
// (room_phy::BandOf); 4 soft bits a tone, in air order. Throws std::invalid_argument for another
// size or a number of tones not from 1 to kBands / 2 (a tone's floor is read where its
// sub-band rests).
std::vector<float> RoomSoftBits(const std::vector<double>& energy, int symbols, int tones = 1);
// Today's packet: its kSymbols rows.
room_code::SoftBits RoomSoftBits(const std::vector<double>& energy);

}  // namespace nava_modem
