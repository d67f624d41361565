#pragma once

#include "nava_bench_args.h"
#include "tool_args/usage_error.h"

namespace nava_modem::tools {

// nava_bench --splice --early A.wav[:K] --late B.wav[:K] --at-ms LIST --out DIR: which span of a
// room's response decides what a receiver makes of it. Writes a.wav and b.wav (the two responses
// at request.sample_rate, mono) and, for each T of request.at_ms, aT_b.wav (A's first T ms, B's
// sound after) and bT_a.wav (B's first T ms, A's sound after), each part at A's energy over its
// span (nava_modem/response_splice.h), and prints each file's RT60 and DRR; `nava_bench --rooms
// --rir-dir DIR` then decodes packets through them. Returns the exit code.
int SpliceTable(const SpliceRequest& request, const multirobot_audio::tools::ToolUsage& usage);

}  // namespace nava_modem::tools
