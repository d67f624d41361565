#pragma once

// The nava receiver's diagnostics: for each break it examines, what each stage made of it (the
// break the detector found and where the known bits settled it, the tone model, the clocks tried
// and each one's reading and verdict, the equaliser's tries, and the event reported), so that a
// packet lost in a room can be traced to the stage that lost it (nava_decode --diagnostics). Off
// unless the receiver is given somewhere to put them (FskReceiver::SetDiagnostics); on or off, the
// receiver decides the same. No ROS.
#include <vector>

#include "nava_modem/clock_search.h"
#include "nava_modem/frame_reading.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/tone_model.h"

namespace nava_modem {

// The receiver counts time in its tone filters' steps (a few samples each) and a clock's rate in
// steps a bit: what turns them into samples, seconds and a rate error.
struct TraceScale {
  double samples_per_step = 1.0;
  double seconds_per_step = 0.0;
  double per_bit = 1.0;  // steps a bit at the nominal rate
  double Samples(double step) const { return step * samples_per_step; }
  double Seconds(double step) const { return step * seconds_per_step; }
  // The sender's rate over the nominal, less 1 (as RxEvent::rate_error), for `period` steps a bit.
  double RateError(double period) const { return per_bit / period - 1.0; }
};

// One clock the search offered, and what was read on it.
struct ClockTrial {
  ClockFit candidate{};  // ClockCandidates' coarse fit
  ClockFit fine{};       // BestClock's refinement of it: the clock the frame was read on
  FrameReading reading;  // ReadFrame's
  RxEvent verdict;       // AcceptReading's: the packet, or the noise class
};

// One clock search: the tone model read at a break and the clocks tried there, best first. A
// break whose clocks read nothing is searched once more where the best clock put it.
struct ClockSearchTrace {
  double break_step = 0.0;  // the break's SPACE-to-MARK step, filter steps
  ToneModel model;
  std::vector<ClockTrial> clocks;
};

// One reading the equaliser was given: at the nominal rate, `shift_bits` whole bits from where
// the best clock put the break; or on the best clock itself (`own_clock`, when it is off the
// nominal rate).
struct EqualizerTrial {
  int shift_bits = 0;
  bool own_clock = false;
  double rate_error = 0.0;
  bool passed = false;  // its frame passed the CRC (repaired by fixed_bits bits)
  int fixed_bits = 0;
};

// How a break ended: the stage that read its packet, or where it was lost.
enum class BreakOutcome {
  kPending,            // not ended yet
  kPacketOnClock,      // a clock's reading passed the acceptance step
  kPacketByEqualizer,  // no clock's reading passed; the equaliser's did
  kNoClock,            // the clock search offered no clock
  kNotRead,            // clocks were read and the equaliser tried; nothing passed: noise
  kSuperseded,         // a clearer or much louder break came before its packet was in
  kMuted,              // the receiver was muted before its packet was in
};
// pending, packet_on_clock, packet_by_equalizer, no_clock, not_read, superseded, muted
const char* BreakOutcomeName(BreakOutcome outcome);

struct BreakTrace {
  TraceScale scale;
  double detected_step = 0.0;  // the detector's estimate of the SPACE-to-MARK step
  double clarity = 0.0;        // how clear the detector's peak was (RxEvent::clarity)
  // Once the break's packet is in, the known bits may move the break (FskReceiver::SettleBreak):
  // the best clock within the search's reach of the estimate (`near`) and across the wide span
  // (`wide`), and the break settled on. Not settled: superseded or muted first.
  bool settled = false;
  ClockFit near{}, wide{};
  double settled_step = 0.0;
  std::vector<ClockSearchTrace> searches;
  std::vector<EqualizerTrial> equalizer;  // in the order tried; empty when not tried
  BreakOutcome outcome = BreakOutcome::kPending;
  // The event reported for it, exactly as reported (its time, clarity and arrival included);
  // none when superseded or muted.
  bool reported = false;
  RxEvent event;
};

// Holds the trace of the break being collected and hands it on when the break ends. With no sink
// it records nothing, and the receiver's only cost is asking.
class BreakTracer {
 public:
  // `sink` gets one trace per break, appended as each break ends; null stops recording.
  void SetSink(std::vector<BreakTrace>* sink);
  // The trace of the break being collected; null when not recording or no break is open.
  BreakTrace* current() { return sink_ != nullptr && open_ ? &current_ : nullptr; }
  // A break found: opens its trace (when recording), handing on any open one as kPending.
  void Begin(const TraceScale& scale, double detected_step, double clarity);
  // Ends the open break with `event` reported for it, its outcome as the stages set it.
  void Report(const RxEvent& event);
  // Ends the open break with no event: superseded or muted.
  void Drop(BreakOutcome why);

 private:
  void Close();
  std::vector<BreakTrace>* sink_ = nullptr;
  BreakTrace current_;
  bool open_ = false;
};

}  // namespace nava_modem
