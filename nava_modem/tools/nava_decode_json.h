#pragma once

// What nava_decode writes: each event as a JSON object (its line on stdout), and with
// --diagnostics each break the nava receiver examined (fsk_diagnostics.h) as a JSON object.
#include <string>

#include "nava_modem/fsk_diagnostics.h"
#include "nava_modem/packet_receiver.h"

namespace nava_modem::tools {

// {"t": end_s, "kind", "noise", "data", "level_db", "quality", "start", "fixed_bits",
// "rate_error", "arrival"} and, with `direction` (an array's decode), "direction" and
// "direction_confidence". One line, no newline.
std::string EventJson(const RxEvent& e, bool direction);

// One break's trace on one line (no newline): times in s from the file's start (6 decimals) and
// samples, clocks as their first MARK bit's time, rate error and fit, each reading's frame bits
// and bytes, how sure its data bits were and its verdict, the equaliser's tries, the outcome and
// the event reported (EventJson's, null when none).
std::string BreakTraceJson(const BreakTrace& trace);

}  // namespace nava_modem::tools
