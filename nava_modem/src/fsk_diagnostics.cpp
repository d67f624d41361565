#include "nava_modem/fsk_diagnostics.h"

#include <utility>

namespace nava_modem {

const char* BreakOutcomeName(BreakOutcome outcome) {
  switch (outcome) {
    case BreakOutcome::kPending: return "pending";
    case BreakOutcome::kPacketOnClock: return "packet_on_clock";
    case BreakOutcome::kPacketByEqualizer: return "packet_by_equalizer";
    case BreakOutcome::kNoClock: return "no_clock";
    case BreakOutcome::kNotRead: return "not_read";
    case BreakOutcome::kSuperseded: return "superseded";
    case BreakOutcome::kMuted: return "muted";
  }
  return "?";
}

void BreakTracer::SetSink(std::vector<BreakTrace>* sink) {
  sink_ = sink;
  open_ = false;  // a break begun for another sink, or unrecorded, is not this sink's
}

void BreakTracer::Begin(const TraceScale& scale, double detected_step, double clarity) {
  if (sink_ == nullptr) return;
  if (open_) Close();
  current_ = BreakTrace{};
  current_.scale = scale;
  current_.detected_step = detected_step;
  current_.clarity = clarity;
  open_ = true;
}

void BreakTracer::Report(const RxEvent& event) {
  if (sink_ == nullptr || !open_) return;
  current_.reported = true;
  current_.event = event;
  Close();
}

void BreakTracer::Drop(BreakOutcome why) {
  if (sink_ == nullptr || !open_) return;
  current_.outcome = why;
  Close();
}

void BreakTracer::Close() {
  sink_->push_back(std::move(current_));
  open_ = false;
}

}  // namespace nava_modem
