#pragma once

// The whine harm curve of a nava decode table (DecodeTable::whine_harm_hz/_db), measured with the
// real receiver: how much more a motor whine of each fundamental frequency harms nava's packets
// than the table's own whine (whine_hz, midway between the tones) of the same power.
//
// Why measured: a whine's harm to a two-tone receiver is set by where its harmonics fall against
// the tones and the receiver's filters, not by its power in the band. The rule of thumb it
// replaces (power weighed by closeness to a tone) was off by up to 10 dB: it took a 1200 Hz fan,
// whose 2nd and 3rd harmonics lie 100 Hz from the tones, as 4.9 dB worse than the table's whine,
// where the receiver finds it 8-9 dB worse, and a 2600 Hz whine as 4 dB worse, where it is 7-8 dB
// kinder (the shipped curve; docs/audio_link.md).
//
// How: for every fundamental from WhineHarmOptions::low_hz to high_hz in step_hz, and for
// whine_hz, packets under the renderer's motor whine (nava_modem::MotorWhine: three harmonics)
// at SIRs from low_sir_db to high_sir_db in sir_step_db, through rooms like measured ones of
// `rt60` and `drr_db` (where the receiver decodes nearly every packet in quiet, so the whine
// alone decides); kWhineHarmPackets packets a SIR. whine_hz itself is in the curve at 0 dB. A
// frequency's harm is how far its delivery curve lies to the right of whine_hz's: the difference
// of the areas under the two curves over whine_hz's plateau (its best quarter of SIRs), times the
// SIR step. Areas, not 50 %
// crossings, so that a few packets' chance does not move it much and a curve that never rises
// counts as the whole range.
#include "table_cells.h"

namespace audio_propagation::tools {

constexpr int kWhineHarmPackets = 16;  // a SIR, for a table's curve (--whine-harm: --packets)

struct WhineHarmOptions {
  double low_hz = 400.0, high_hz = 4400.0, step_hz = 25.0;
  double low_sir_db = -24.0, high_sir_db = 12.0, sir_step_db = 3.0;
  double rt60 = 0.5, drr_db = 3.0;
  int threads = 2;
};

// Fills `table`'s whine_harm_hz and whine_harm_db (s.table.packets packets a SIR), printing a
// line per frequency to stdout. Throws std::invalid_argument for a table that is not nava's or
// options out of order, std::runtime_error when the reference whine leaves under half the packets
// at its best (no curve can be read against it).
void MeasureWhineHarm(CellSetup s, const WhineHarmOptions& options, DecodeTable& table);

}  // namespace audio_propagation::tools
