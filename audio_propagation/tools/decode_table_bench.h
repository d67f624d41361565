#pragma once

// decode_table_bench: measures a profile's decode table (audio_propagation/decode_table.h) with
// its real receiver (nava_modem's) on rendered room audio. The tables it writes are shipped in
// audio_propagation/tables/ and read by the `acoustic` channel model.
//
//   decode_table_bench --profile nava|room [--out FILE] [--packets 12] [--quick] [--threads 2]
//                      [--seed 1] [--dir DIR] [--snr-db LIST] [--rt60 LIST]
//                      [--response statistical|measured-like]
//
//   decode_table_bench --profile nava --whine-harm [--table FILE] [--out FILE] [--packets 16] [--quick]
//
// (Tables made before the tool moved here name the same measurement `nava_bench --table PROFILE`.)
//
// A nava table (not --quick) also gets its whine harm curve (whine_harm.h); --whine-harm measures
// that curve alone into a copy of --table (the shipped one by default), its cells kept.
//
// Axes: SNR -15, -12, -9, -6, -3, 0, 3, 6, 9, 12, 18, 30 dB (room from -27 dB: see the code),
// DRR -30, -24, -18, -12, -6, 0, 6, 12, 24 dB, RT60 0.3, 0.6, 1.2 s, every kind; --quick: SNR
// -12, 0, 12, DRR -18, 0, 18, RT60 0.5, 4 packets a cell (for tests); --snr-db -30,-27,...
// replaces the SNR axis, --rt60 0.3,0.6,... the RT60 axis. The profile runs at its default
// options (48 kHz).
// For every cell (kind, rt60, DRR, SNR) N packets of random data, each alone in its own recording
// through its own room (RenderRoom, a seed per packet and cell: its own impulse response and
// stretch of noise; --response: the statistical room, or rooms like measured ones:
// measured_like_response.h), with the cell's disturbance at the cell's SNR:
//   white, pink  RoomOptions' noise at snr_db = SNR;
//   speech       make_speech.sh's speech as the interferer at sir_db = SNR, a random stretch per
//                packet, over a faint white floor (below);
//   whine        the table's whine_hz at whine_sir_db = SNR, over the floor;
//   packet       another packet of the profile (other data) through its own room of the same
//                rt60 and DRR, at SNR below the wanted one (both powers by room_channel.h's
//                definition: the mean square over the samples where each sounds), starting
//                anywhere within 0.9 packet lengths before or after it, over the floor.
// The floor is white noise 20 dB below the disturbance and at least 40 dB below the signal (the
// --rooms rows' floor), so speech's pauses are not digital silence; it adds at most 0.04 dB to
// the disturbance, so the disturbance's kind alone sets the cell.
//
// The receiver (the profile's own, with the tools' carrier threshold, so busy air is reported as
// ZERO_BYTE as nava_decode does) decodes each recording, and the packet counts as: decoded (a
// packet with its data); else, if the interferer's packet was decoded, nothing (the receiver
// was taken by the other sender, whose packet the simulated channel judges on its own link);
// else the most telling noise the receiver reported overlapping the packet's time, BAD_CRC
// over ONE_BYTE over ZERO_BYTE; else nothing. A packet with data never sent (a CRC passed by
// chance) is not the wanted one; the summary counts them.
//
// Cells run on --threads threads; each is seeded by its index, so the table does not depend on
// the thread count. Progress goes to stderr; the summary (delivery against SNR for every kind at
// the rt60 and DRR nearest 0.6 s and 0 dB) and the CPU time to stdout.
#include <string>

#include "decode_table_bench_args.h"

namespace audio_propagation::tools {

// Measures and writes the table; `usage` refuses an --out in no folder.
int DecodeTableBench(const DecodeTableRequest& request);

}  // namespace audio_propagation::tools
