#pragma once

#include "nava_bench_args.h"
#include "tool_args/usage_error.h"

namespace nava_modem::tools {

// nava_bench --likeness --rir-dir DIR: how like the renderer's rooms (MeasuredLikeResponse) are
// to measured ones. For every room of request.rir_dir, its features (response_features.h) beside
// the median of request.rooms measured-like rooms drawn at its RT60 and DRR: a line per room,
// then, for each feature, the median and the 10th and 90th percentiles of the difference
// (measured-like less measured) over all rooms and over three DRR classes (at or above 0 dB, -6
// to 0 dB, below -6 dB). Nothing is decoded: it says where the rooms a table is measured over
// differ from yours before any packet is sent. Returns the exit code.
int LikenessTable(const LikenessRequest& request, const multirobot_audio::tools::ToolUsage& usage);

}  // namespace nava_modem::tools
