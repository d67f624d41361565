#pragma once

#include "nava_bench_args.h"

namespace nava_modem::tools {

// nava_bench --link-cost: what timing packets for ranging (RxEvent::arrival and the link's own
// timings) adds to a link's CPU. A NavaLink runs on a simulated sound card whose microphone
// hears its own speaker (an unknown loop delay) and two teammates, each sending a packet every
// request.period seconds, for request.seconds of audio, with time_arrivals on and off, as fast
// as it can; the least CPU of request.runs runs each. Prints both, their ratio, the timings
// made, and the target (at most 10 % more). Returns the exit code.
int LinkCostTable(const LinkCostRequest& request);

}  // namespace nava_modem::tools
