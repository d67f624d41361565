#pragma once

#include "nava_bench_args.h"
#include "tool_args/usage_error.h"

namespace nava_modem::tools {

// nava_bench --arrival: room packets played through every measured room of request.rir_dir
// (the response's own delay kept) with white noise at request.snr_db, decoded by the room
// receiver; each packet's "arrival" against the instant it was sent plus the response's leading
// edge (first_arrival.h). A line per room (packets timed, median, 90th percentile and largest
// error, and the jitter: the 90th percentile of each packet's distance from the room's own
// median), then the totals over the rooms at or above request.min_drr_db and the targets (median
// within 0.1 ms, 90th percentile within 0.3 ms), and the jitter over every room (target: within
// 0.1 ms in each). Returns the exit code.
int ArrivalTable(const ArrivalRequest& request, const multirobot_audio::tools::ToolUsage& usage);

}  // namespace nava_modem::tools
