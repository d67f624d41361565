#pragma once

#include "nava_bench_args.h"
#include "tool_args/usage_error.h"

namespace nava_modem::tools {

// nava_bench --direction: what a robot's microphone array reports of where a packet came from,
// room by room. For each cell of a grid of reverberation times and direct-to-reverberant
// ratios, packets from random bearings rendered to the two arrays the simulated microphones
// stand for (omni: a 10 cm square of four; bidirectional: a pair 0.2 m apart on the robot's x
// axis) by nava_room's array renderer (measured-like responses, noise at request.snr_db), and
// decoded as the link does it (DecodeArray): a line per cell (packets decoded, the square's
// median and 90th-percentile error, the pair's right, wrong and missing bits). With
// request.binaural_dir, the same pair judged on measured dummy-head responses whose file names
// give the head's azimuth (`..._headaz+40.wav`: the source at minus that azimuth), beside the
// rendered cell nearest each ear's RT60 and DRR. With request.errors_out, every decoded packet's
// (true bearing, estimate, confidence) per cell and array: the table the simulated microphones
// draw from (audio_propagation/direction_errors_file.h). Returns the exit code.
int DirectionTable(const DirectionRequest& request, const multirobot_audio::tools::ToolUsage& usage);

}  // namespace nava_modem::tools
