#pragma once

#include <complex>
#include <cstdint>
#include <optional>
#include <vector>

#include "nava_modem/clock_search.h"
#include "nava_modem/break_detector.h"
#include "nava_modem/busy_air.h"
#include "nava_modem/frame_reading.h"
#include "nava_modem/frame_repair.h"
#include "nava_modem/fsk_diagnostics.h"
#include "nava_modem/fsk_equalizer.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/nava_packet_timer.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/tone_filters.h"
#include "nava_modem/tone_model.h"
#include "nava_modem/tone_ring.h"

namespace nava_modem {

// The Nava demodulator. Samples pass the two tone filters (ToneFilters), whose outputs a ToneRing
// keeps. The break before each packet is found by its SPACE-to-MARK step (BreakDetector, the
// first stage; its peak and the state around it are this class's), seen both in the tones' sum
// and tone by tone (a room can leave one tone 10 dB or more below the other, and the strong
// tone's tail then hides the step in the sum), and moved to where the clock that best explains
// the packet's known bits puts it when that lies beyond the clock search's reach (a faint tone or
// a room's tail can make the detector's estimate up to a window late, and a dip in SPACE's sound
// 10 bits early; a packet whose break moves later is reported once it is in). Each tone's level
// and floor (and a room's tail) are read from the break (FitToneModel, the second stage), so
// that a tone weaker than the other counts as much; the bit clock (clock_search.h) is fitted to
// the break, the start and stop bits and the header (bit rate and phase, by
// maximum likelihood over the packet), then a digital PLL (BitClock) follows the data's
// transitions; each bit's soft decision is a log-likelihood ratio of the two tones' powers
// against their levels and floors (read again from the frame itself, as a room colours the
// break's steady tones), the emulated UART reads 8N1 characters from them (the frame reader's
// FrameReading; AcceptReading, the acceptance step, does the rest), and the CRC repairs
// up to two unsure bits (one in a reading on the break's own model, which a room's echoes can
// make sure of wrong bits; none on a clock more than 1.5 % off the nominal rate, where wrong
// fits land). When no clock's reading passes, the break is placed where the best clock put
// it, the tone model read there and the clocks searched once more; then the
// equaliser (FskEqualizer) reads the packet again from the filters' complex outputs, with a
// model of the room's echoes fitted to the packet itself: on the nominal bit rate from where
// the best clock put the break and up to two bits either side (echoes a bit or two late pull
// the best clock late or fast), then on the best clock itself if it is off the nominal rate.
class FskReceiver : public PacketReceiver {
 public:
  // Throws std::invalid_argument for impossible options (ValidateModemOptions,
  // ValidateReceiverOptions).
  FskReceiver(const ModemOptions& modem, const ReceiverOptions& options);

  void Process(const float* samples, std::size_t count, std::vector<RxEvent>& events) override;
  void Flush(std::vector<RxEvent>& events) override;
  void SetMuted(bool muted) override;
  void SetCarrierThreshold(std::optional<double> db) override;
  // In-band level of the last bit, dB of full scale.
  double level_db() const override;
  double time() const override { return Seconds(static_cast<double>(n_)); }
  // Appends a trace of each break examined from now on to `traces` (fsk_diagnostics.h), which
  // must outlive the receiver or the next call; null (the default) records nothing. What is
  // decoded is the same either way.
  void SetDiagnostics(std::vector<BreakTrace>* traces) { tracer_.SetSink(traces); }

 private:
  enum class State { kSearching, kPeaking, kCollecting };
  void Step(std::vector<RxEvent>& events);  // one filter output
  void TrackCarrier(double e, std::vector<RxEvent>& events);
  // Where the frame after a break at break_step is in, with the sender's clock as slow as allowed.
  std::int64_t DecodeAt(double break_step) const;
  // The break the packet's known bits place best, from the detector's estimate break_step.
  double SettleBreak(double break_step);
  RxEvent DecodeFrame(double break_step);
  // The tone filters' normalised difference (normalized_) over a packet whose break lies from
  // earliest_break to latest_break.
  void Normalize(double earliest_break, double latest_break);
  // The tone model read at break_step, the clocks searched around it and read in turn: nullopt
  // when one reads a packet (then in `first`); else the best clock's fine fit (metric -1e300
  // when there was none), its reading in `first` and where its bits were read.
  std::optional<ClockFit> ReadOnBestClocks(double break_step, RxEvent& first, std::int64_t* first_at);
  // The tone filters' complex outputs at at_step (kPacketBits steps), and those steps in samples.
  void Outputs(const std::int64_t* at_step, std::complex<double> heard[2][kPacketBits], double* at) const;
  // The equaliser's reading of the packet with its bits' filter outputs taken at at_step
  // (kPacketBits steps, the break's first SPACE bit first), the sender's clock rate_error off.
  std::optional<RepairedFrame> Equalize(const std::int64_t* at_step, double rate_error) const;
  double Seconds(double step) const { return step * seconds_per_step_; }
  TraceScale Scale() const;

  ModemOptions modem_;
  ReceiverOptions options_;
  ToneFilters filters_;
  NavaPacketTimer timer_;  // each packet's first arrival
  // Time inside the receiver runs in the filters' steps (a few samples each).
  double per_bit_;    // steps per bit
  double seconds_per_step_;
  std::int64_t w_;    // steps in each half of the break detector
  ToneRing ring_;     // the filters' outputs, per step
  BreakDetector detector_;
  FskEqualizer equalizer_;
  std::int64_t n_ = 0;  // steps processed
  State state_ = State::kSearching;
  double peak_ = 0.0, peak_power_ = 0.0;  // the clearest step so far, and its windows' power
  std::int64_t peak_at_ = 0, decode_at_ = 0, blank_until_ = 0;
  double break_step_ = 0.0;  // estimated sample where the break turns from SPACE to MARK
  bool break_settled_ = false;  // break_step_ is SettleBreak's, not the detector's
  bool break_moved_late_ = false;  // and SettleBreak moved it later
  ToneModel model_;          // of the packet being decoded
  NormalizedTones normalized_;  // over the packet being decoded (Normalize)
  bool muted_ = false;
  BusyAir busy_{0.0, 0.0};  // for ZERO_BYTE reports
  BreakTracer tracer_;  // the diagnostics, when asked for
};

}  // namespace nava_modem
