#include "nava_decode_json.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "modem_args.h"
#include "nava_modem/frame.h"
#include "tool_args/json_text.h"

namespace nava_modem::tools {
namespace {

using multirobot_audio::tools::JsonNumber;
using multirobot_audio::tools::JsonSignificant;

// printf's text as a string, however long.
__attribute__((format(printf, 1, 2))) std::string Format(const char* format, ...) {
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string out(static_cast<std::size_t>(std::max(size, 0)) + 1, '\0');
  std::vsnprintf(out.data(), out.size(), format, again);
  va_end(again);
  out.pop_back();  // vsnprintf's terminating NUL
  return out;
}

// JSON has no NaN: a direction the array cannot tell is null.
std::string DirectionJson(const RxEvent& e) {
  if (std::isnan(e.direction)) return Format(", \"direction\": null, \"direction_confidence\": %.2f", e.direction_confidence);
  return Format(", \"direction\": %.4f, \"direction_confidence\": %.2f", e.direction, e.direction_confidence);
}

// The packet's first arrival, 6 decimals (a microsecond); null where it was not timed.
std::string ArrivalJson(const RxEvent& e) {
  if (std::isnan(e.arrival)) return ", \"arrival\": null";
  return Format(", \"arrival\": %.6f", e.arrival);
}

// A time in the file, s (to a microsecond).
std::string Seconds(const TraceScale& scale, double step) { return JsonNumber(scale.Seconds(step), 6); }

// A position in the file, s and samples: an object's first fields.
std::string PositionFields(const TraceScale& scale, double step) {
  return "\"s\": " + Seconds(scale, step) + ", \"sample\": " + JsonNumber(scale.Samples(step), 1);
}

// A clock by its first MARK bit, its rate and its fit (null: no fit).
std::string ClockJson(const TraceScale& scale, const ClockFit& clock) {
  return "{\"first_mark_s\": " + Seconds(scale, clock.start) + ", \"rate_error\": " + JsonNumber(scale.RateError(clock.period), 5) +
         ", \"metric\": " + (clock.metric > -1e299 ? JsonSignificant(clock.metric, 6) : "null") + "}";
}

std::string PairJson(const double (&pair)[2]) {
  return "[" + JsonSignificant(pair[0], 6) + ", " + JsonSignificant(pair[1], 6) + "]";
}

// The tone model: each tone's (MARK's, SPACE's) level, floor and tail, and the tail's decay and gain.
std::string ModelJson(const ToneModel& m) {
  return "{\"level\": " + PairJson(m.level) + ", \"floor\": " + PairJson(m.floor) + ", \"decay\": " + JsonSignificant(m.decay, 6) +
         ", \"gain\": " + JsonSignificant(m.gain, 6) + ", \"tail\": " + PairJson(m.tail) + "}";
}

// What a verdict says: packet, or the noise class.
const char* VerdictName(const RxEvent& e) { return e.kind == RxEvent::Kind::kPacket ? "packet" : NoiseName(e.noise); }

// A reading: the frame's hard bits a character (start, 8 data bits, stop) at a time, the bytes
// the UART reads from them and which characters it framed, how sure the data bits were (the
// least and the mean magnitude of their log-likelihood ratios on the break's model), its level,
// quality and times, and the acceptance step's verdict.
std::string ReadingJson(const FrameReading& r, const RxEvent& verdict) {
  std::string bits, framed;
  std::vector<std::uint8_t> bytes;
  for (int c = 0; c < kFrameBytes; ++c) {
    if (c > 0) bits += ' ';
    for (int b = 0; b < kBitsPerByte; ++b) bits += r.hard[static_cast<std::size_t>(c * kBitsPerByte + b)] ? '1' : '0';
    const UartByte byte = ReadUartByte(r.hard.data() + c * kBitsPerByte);
    bytes.push_back(byte.value);
    framed += byte.framed ? '1' : '0';
  }
  double least = 1e300, sum = 0.0;
  for (const float llr : r.soft) {
    least = std::min(least, std::abs(static_cast<double>(llr)));
    sum += std::abs(static_cast<double>(llr));
  }
  return "{\"start_s\": " + JsonNumber(r.start, 6) + ", \"end_s\": " + JsonNumber(r.end, 6) + ", \"rate_error\": " +
         JsonNumber(r.rate_error, 5) + ", \"level_db\": " + JsonNumber(r.level_db, 1) + ", \"quality\": " + JsonNumber(r.quality, 3) +
         ", \"bits\": \"" + bits + "\", \"bytes\": \"" + HexBytes(bytes) + "\", \"framed\": \"" + framed +
         "\", \"soft_min\": " + JsonNumber(least, 2) + ", \"soft_mean\": " + JsonNumber(sum / static_cast<double>(r.soft.size()), 2) +
         ", \"verdict\": \"" + VerdictName(verdict) + "\", \"fixed_bits\": " + std::to_string(verdict.fixed_bits) + "}";
}

std::string SearchJson(const TraceScale& scale, const ClockSearchTrace& search) {
  std::string clocks;
  for (const ClockTrial& c : search.clocks) {
    if (!clocks.empty()) clocks += ", ";
    clocks += "{\"candidate\": " + ClockJson(scale, c.candidate) + ", \"fine\": " + ClockJson(scale, c.fine) +
              ", \"reading\": " + ReadingJson(c.reading, c.verdict) + "}";
  }
  return "{\"break\": {" + PositionFields(scale, search.break_step) + "}, \"model\": " + ModelJson(search.model) + ", \"clocks\": [" +
         clocks + "]}";
}

std::string EqualizerJson(const EqualizerTrial& t) {
  return "{\"shift_bits\": " + std::to_string(t.shift_bits) + ", \"own_clock\": " + (t.own_clock ? "true" : "false") +
         ", \"rate_error\": " + JsonNumber(t.rate_error, 5) + ", \"passed\": " + (t.passed ? "true" : "false") +
         ", \"fixed_bits\": " + std::to_string(t.fixed_bits) + "}";
}

}  // namespace

std::string EventJson(const RxEvent& e, bool direction) {
  return Format("{\"t\": %.3f, \"kind\": \"%s\", \"noise\": \"%s\", \"data\": \"%s\", \"rate\": %d, \"level_db\": %.1f, "
                "\"quality\": %.2f, \"start\": %.3f, \"fixed_bits\": %d, \"rate_error\": %.4f%s%s}",
                e.end, e.kind == RxEvent::Kind::kPacket ? "packet" : "noise", NoiseName(e.noise), HexBytes(e.data).c_str(),
                e.rate, e.level_db, e.quality, e.start, e.fixed_bits, e.rate_error, ArrivalJson(e).c_str(),
                direction ? DirectionJson(e).c_str() : "");
}

std::string BreakTraceJson(const BreakTrace& trace) {
  const TraceScale& scale = trace.scale;
  std::string settled = "null";
  if (trace.settled) {
    settled = "{" + PositionFields(scale, trace.settled_step) + ", \"near\": " + ClockJson(scale, trace.near) + ", \"wide\": " + ClockJson(scale, trace.wide) + "}";
  }
  std::string searches, equalizer;
  for (const ClockSearchTrace& s : trace.searches) searches += (searches.empty() ? "" : ", ") + SearchJson(scale, s);
  for (const EqualizerTrial& t : trace.equalizer) equalizer += (equalizer.empty() ? "" : ", ") + EqualizerJson(t);
  return "{\"detected\": {" + PositionFields(scale, trace.detected_step) + ", \"clarity\": " + JsonNumber(trace.clarity, 3) +
         "}, \"settled\": " + settled + ", \"searches\": [" + searches + "], \"equalizer\": [" + equalizer +
         "], \"outcome\": \"" + BreakOutcomeName(trace.outcome) + "\", \"event\": " +
         (trace.reported ? EventJson(trace.event, false) : "null") + "}";
}

}  // namespace nava_modem::tools
