#pragma once

// The acoustic channel model held against measured rooms (decode_table_bench --calibrate): every
// room of a folder (or folders) of measured impulse responses (each channel of each file, as nava_bench
// --rir-dir reads them), packets at each full-band SNR in white noise and, with --noise-file, in
// that recorded noise, decoded by the profile's real receiver (decode_table_bench's cells, the
// packets heard through the measured response) and predicted by the model from the response's
// RT60 and DRR (as audio_channel_predict predicts them). Prints a line per (room, noise, SNR)
// case, then the cases pooled into bins of predicted probability 0-20, 20-60 and 60-100 % with
// each bin's mean prediction and mean decoded, and ends
//   calibration: worst bin N points apart (the target: within 10)
#include "decode_table_bench_args.h"

namespace audio_propagation::tools {

int CalibrateModel(const DecodeTableRequest& request);

}  // namespace audio_propagation::tools
