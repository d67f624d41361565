#pragma once

#include "nava_bench_args.h"
#include "tool_args/usage_error.h"

namespace nava_modem::tools {

// nava_bench --frames --rir-dir DIR: frames of request.bytes random data bytes at each of the
// profile's rates (or request.speeds) through every measured room of DIR (every channel of
// every file a room-ear), under white noise at full-band SNR request.snr_db and, with
// request.noise_file, under that recording at the same level; decoded by the profile's receiver
// in-process. A line per room-ear (its DRR and RT60, then per condition and rate the frames
// decoded right of those sent and any wrong), then per rate and condition the room-ears with at
// least 19 in 20 (95 %), the frames pooled, the wrong ones, and the decoder's speed (seconds of
// audio per CPU second), with the frames-and-rates targets. Returns the exit code.
int FrameTable(const FramesRequest& request, const multirobot_audio::tools::ToolUsage& usage);

}  // namespace nava_modem::tools
