#include "nava_modem/fsk_receiver.h"

#include <algorithm>
#include <cmath>

#include "nava_modem/clock_search.h"
#include "nava_modem/frame_reading.h"
#include "nava_modem/math_constants.h"
#include "nava_modem/power_of_two.h"

namespace nava_modem {
namespace {

constexpr int kDetectorBits = 10;  // each half of the break detector
// After the detector first passes its threshold, the strongest step within this many bits is
// taken as the break: noise can pass the threshold just before a real break arrives.
constexpr int kPeakWindowBits = 10;
// A step this much clearer than the break being collected replaces it. Real breaks are far
// clearer than noise (0.55 at -12 dB against at most 0.5 in noise alone); the MARK-then-SPACE
// patterns that data can hold are not.
constexpr double kSupersede = 0.2;
// So does a step past the threshold this many times louder: a break heard in the quiet before
// a packet (noise passes the threshold now and then) must not hide the packet's own break.
constexpr double kLouder = 10.0;
// Phases searched either side of the detector's estimate of the break, in bits: a room's tail
// of the SPACE half delays the step the detector sees by a bit or two.
constexpr double kPhaseSpanBits = 2.5;
// The break is also looked for this many bits before the detector's estimate and this many after
// it (SettleBreak), and moved there when its clock explains the known bits by this factor better
// than any near one. Late: a cluster of reflections in opposite phase can dip SPACE by 6 to 11 dB
// some 30 to 60 ms after it began, and the detector takes the dip for the break, 9 or 10 bits
// early (a concert hall's and a museum basement's measured responses, made drier).
constexpr double kWideEarlyBits = 12.0, kWideLateBits = 12.0;
constexpr double kFarBreakGain = 1.1;
// Bit clocks tried per packet (see DecodeFrame).
constexpr std::size_t kClockHypotheses = 3;
// Where the equaliser reads a packet no clock read (DecodeFrame): on the nominal bit rate from
// where the best clock put the break, and up to this far later and earlier, in whole bits
// (earlier further: a room's echoes and tail make the break look late, by up to 5 bits through
// a clap's spread direct sound measured on a dummy head, and by 6 where a first arrival comes
// 3 bits before the loudest one, as in a measured seminar room made drier; 9 stays within the
// 12 bits the wide break search covers early); then on the best clock itself when
// its rate is more than kEqualizerOwnClockRate off the nominal one (the equaliser searches the
// sender's offset 0.3 % either side of the rate it is given; a clock that put a -0.5 % sender at
// -0.25 % once read packets the nominal rate could not). Half-bit steps read a few more packets
// in measured rooms, but a reading between two bits lets the equaliser, trained on the known
// header, make that header out of a wrong one (Modem.EachNoiseClassOnPurpose).
constexpr int kEqualizerLateBits = 2, kEqualizerEarlyBits = 9;
constexpr double kEqualizerOwnClockRate = 0.001;
// Error events of the equaliser's search tried as repairs (RepairEvent): the weakest this many
// of 2 to kMaxEventBits bits. A concert hall's tail beyond the equaliser's reach left packets
// whose only errors were one 3-bit event; the equaliser's two-bit errors are nearly all one
// event too (a transition moved by a bit), see Equalize.
constexpr int kEventRepairs = 3, kMaxEventBits = 4;

// Filter outputs kept: the packet and the clock search's reach either side.
std::size_t RingSize(double per_bit) { return PowerOfTwoAtLeast(150.0 * per_bit + 64.0); }

}  // namespace

FskReceiver::FskReceiver(const ModemOptions& modem, const ReceiverOptions& options)
    : modem_((ValidateModemOptions(modem), modem)), options_((ValidateReceiverOptions(options), options)), filters_(modem),
      timer_(modem, options.max_rate_error),
      per_bit_(SamplesPerBit(modem) / filters_.step()), seconds_per_step_(filters_.step() / modem.sample_rate),
      w_(static_cast<std::int64_t>(std::lround(kDetectorBits * per_bit_))),
      ring_(RingSize(per_bit_)),
      detector_(w_),
      equalizer_(modem) {
  // Busy air with no frame, at least a bit long, ends after a bit of quiet.
  busy_ = BusyAir(Seconds(per_bit_), Seconds(per_bit_));
  SetCarrierThreshold(options_.carrier_threshold_db);
}

void FskReceiver::SetCarrierThreshold(std::optional<double> db) {
  options_.carrier_threshold_db = db;
  busy_.SetThreshold(db);
}

TraceScale FskReceiver::Scale() const { return {static_cast<double>(filters_.step()), seconds_per_step_, per_bit_}; }

double FskReceiver::level_db() const { return 10.0 * std::log10(ring_.sum(n_ - 1) + kTiny); }

void FskReceiver::SetMuted(bool muted) {
  if (muted && !muted_) {
    if (state_ == State::kCollecting) tracer_.Drop(BreakOutcome::kMuted);
    state_ = State::kSearching;
    busy_.Reset();
  }
  if (!muted && muted_) blank_until_ = std::max(blank_until_, n_ + 2 * w_);
  muted_ = muted;
}

void FskReceiver::Process(const float* samples, std::size_t count, std::vector<RxEvent>& events) {
  for (std::size_t k = 0; k < count; ++k) {
    timer_.Push(samples[k]);
    if (filters_.Push(samples[k])) Step(events);
  }
}

void FskReceiver::Flush(std::vector<RxEvent>& events) {
  const std::size_t tail = filters_.step() * (static_cast<std::size_t>(std::ceil((kWideLateBits + kEndBitFromMark + 4) * per_bit_ * (1.0 + options_.max_rate_error))) +
                                               static_cast<std::size_t>(2 * w_));
  const std::vector<float> silence(tail, 0.0f);
  Process(silence.data(), silence.size(), events);
}

void FskReceiver::Step(std::vector<RxEvent>& events) {
  const std::int64_t n = n_;
  ring_.Put(n, filters_.mark_power(), filters_.space_power(), {filters_.mark_re(), filters_.mark_im()},
            {filters_.space_re(), filters_.space_im()});
  detector_.Update(ring_, n);
  ++n_;
  if (muted_) return;
  TrackCarrier(ring_.sum(n), events);
  if (n < 2 * w_) return;
  const double step = detector_.Step();

  switch (state_) {
    case State::kSearching:
      if (n >= blank_until_ && step > options_.detect_threshold) {
        state_ = State::kPeaking;
        peak_ = step;
        peak_at_ = n;
        peak_power_ = detector_.power();
      }
      break;
    case State::kPeaking:
      if (step > peak_) {
        peak_ = step;
        peak_at_ = n;
        peak_power_ = detector_.power();
      } else if (n - peak_at_ > kPeakWindowBits * per_bit_) {
        // The windows' boundary sits on the filters' zero crossing, which lags the step by
        // half a window.
        break_step_ = peak_at_ - w_ - filters_.window() / 2.0 + 1.5;
        decode_at_ = DecodeAt(break_step_);
        break_settled_ = false;
        state_ = State::kCollecting;
        tracer_.Begin(Scale(), break_step_, peak_);
      }
      break;
    case State::kCollecting:
      if (step > peak_ + kSupersede || (step > options_.detect_threshold && detector_.power() > kLouder * peak_power_)) {
        // A much clearer or louder break than the one being collected: that one was noise.
        tracer_.Drop(BreakOutcome::kSuperseded);
        state_ = State::kPeaking;
        peak_ = step;
        peak_at_ = n;
        peak_power_ = detector_.power();
      } else if (n >= decode_at_) {
        if (!break_settled_) {
          // Once a break's packet is in, the break may move; a later one's packet is waited for
          // (only then: every other packet is reported as soon as it is in).
          break_settled_ = true;
          const double detected = break_step_;
          break_step_ = SettleBreak(break_step_);
          break_moved_late_ = break_step_ > detected;
          decode_at_ = DecodeAt(break_step_);
          if (n < decode_at_) return;  // its packet is not in yet
        }
        events.push_back(DecodeFrame(break_step_));
        events.back().clarity = peak_;
        if (options_.time_arrivals && events.back().kind == RxEvent::Kind::kPacket) events.back().arrival = timer_.Time(events.back().start);
        tracer_.Report(events.back());
        busy_.FrameFound();
        // No new break before the detector's windows have left this packet: its tail
        // followed by silence could pass for a step. Not after a faint step that decoded to
        // nothing: that was noise, and a packet's break may be arriving just now. Nor after a
        // step the known bits moved later that decoded to nothing: the move took it towards
        // whatever follows, often a packet after speech (six measured rooms made drier, with
        // speech at SIR 0 dB: 8 rows got a packet or two back without this blanking).
        const bool packet = events.back().kind == RxEvent::Kind::kPacket;
        if (packet || (peak_ >= options_.detect_threshold + kSupersede && !break_moved_late_)) {
          blank_until_ = static_cast<std::int64_t>(events.back().end / seconds_per_step_) + 2 * w_;
        }
        state_ = State::kSearching;
      }
      break;
  }
}

void FskReceiver::TrackCarrier(double e, std::vector<RxEvent>& events) {
  // Busy air ends after a bit of quiet; a frame being decoded is waited for.
  const std::int64_t n = n_ - 1;
  busy_.Step(Seconds(static_cast<double>(n)), e, ring_.amplitude_sum(n), state_ != State::kSearching, events);
}

void FskReceiver::Normalize(double earliest_break, double latest_break) {
  const double margin = (1.0 + options_.max_rate_error) * per_bit_;
  const std::int64_t from = static_cast<std::int64_t>(std::floor(earliest_break + (kFirstBitFromMark - 2) * margin));
  const std::int64_t to = static_cast<std::int64_t>(std::ceil(latest_break + (kEndBitFromMark + 2) * margin));
  // What is not heard yet (a late break's packet) gives no evidence either way.
  normalized_ = NormalizedTones(ring_, model_, from, to, n_);
}

std::optional<ClockFit> FskReceiver::ReadOnBestClocks(double break_step, RxEvent& first, std::int64_t* first_at) {
  // Each tone on its own scale, so that a tone weaker than the other (the speaker's, the
  // room's and the microphone's responses tilt the spectrum) weighs as much in the clock fit.
  model_ = FitToneModel(ring_, break_step, per_bit_);
  Normalize(break_step, break_step);
  // The bit clock that best explains the packet's known bits and the strength of its unknown
  // ones, over a grid of phases for each rate. In deep noise the best fit can be a wrong one,
  // so the best few rates that are local optima are each refined on a finer grid and read in
  // turn; the first whose frame checks is the packet.
  const std::vector<ClockFit> candidates =
      ClockCandidates(normalized_, break_step, per_bit_, kPhaseSpanBits * per_bit_, options_.max_rate_error, kClockHypotheses);
  ClockSearchTrace* search = nullptr;
  if (BreakTrace* trace = tracer_.current()) search = &trace->searches.emplace_back(ClockSearchTrace{break_step, model_, {}});
  ClockFit best{break_step, per_bit_, -1e300};
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const ClockFit fine =
        BestClock(normalized_, candidates[k].start, candidates[k].period, per_bit_ / 16.0, per_bit_ / 64.0, kClockRateStep, 0.0005);
    const FrameReading reading = ReadFrame({ring_, model_, normalized_, filters_.window(), per_bit_, seconds_per_step_}, fine.start, fine.period);
    RxEvent ev = AcceptReading(reading, modem_.crc, options_.max_fixed_bits);
    if (search != nullptr) search->clocks.push_back({candidates[k], fine, reading, ev});
    if (ev.kind == RxEvent::Kind::kPacket) {
      first = ev;
      return std::nullopt;
    }
    if (k == 0) {
      best = fine;
      first = ev;
      std::copy(reading.at.begin(), reading.at.end(), first_at);
    }
  }
  return best;
}

std::int64_t FskReceiver::DecodeAt(double break_step) const {
  return static_cast<std::int64_t>(std::ceil(break_step + (kEndBitFromMark + 1) * per_bit_ * (1.0 + options_.max_rate_error) + per_bit_));
}

double FskReceiver::SettleBreak(double break_step) {
  // In a reverberant room or deep noise the detector's peak can lie up to a window late (a
  // faint MARK's rise, or SPACE's tail falling, is as clear whether or not the windows
  // straddle the break), or a dip in SPACE's sound can pass for the break, beyond the clock
  // search's reach. The clock that best explains the packet's known bits at the nominal rate,
  // from kWideEarlyBits early to kWideLateBits late, moves the break there when it explains them
  // clearly better than any within reach; else the detector's estimate stands (the tone model is
  // read best there). A late clock's last bits are not heard yet and count for nothing here
  // (Normalize), so a late break must win on fewer bits.
  model_ = FitToneModel(ring_, break_step, per_bit_);
  Normalize(break_step - kWideEarlyBits * per_bit_, break_step + kWideLateBits * per_bit_);
  const double span = (kWideEarlyBits + kWideLateBits) / 2.0 * per_bit_;
  const ClockFit wide = BestClock(normalized_, break_step + kWideLateBits * per_bit_ - span, per_bit_, span, per_bit_ / 4.0, 0.0, 1.0);
  const ClockFit near = BestClock(normalized_, break_step, per_bit_, kPhaseSpanBits * per_bit_, per_bit_ / 4.0, 0.0, 1.0);
  const double settled =
      std::abs(wide.start - break_step) > kPhaseSpanBits * per_bit_ && wide.metric > kFarBreakGain * near.metric ? wide.start : break_step;
  if (BreakTrace* trace = tracer_.current()) {
    trace->settled = true;
    trace->near = near;
    trace->wide = wide;
    trace->settled_step = settled;
  }
  return settled;
}

RxEvent FskReceiver::DecodeFrame(double break_step) {
  RxEvent first;
  std::int64_t first_at[kPacketBits];
  bool any_clock = false;
  BreakTrace* const trace = tracer_.current();
  const auto outcome = [trace](BreakOutcome o) {
    if (trace != nullptr) trace->outcome = o;
  };
  // The tone model is read at the settled break (SettleBreak); where the best clock puts the break a
  // quarter bit or more from it (a room's tail can move the detector's peak by a bit), the model
  // is read again there and the clocks searched again, once.
  for (int round = 0; round < 2; ++round) {
    const std::optional<ClockFit> best = ReadOnBestClocks(break_step, first, first_at);
    if (!best) {
      outcome(BreakOutcome::kPacketOnClock);
      return first;
    }
    any_clock = any_clock || best->metric > -1e300;
    if (round == 1 || !(best->metric > -1e300) || std::abs(best->start - break_step) < per_bit_ / 4.0) break;
    break_step = best->start;
  }
  if (!any_clock) {
    outcome(BreakOutcome::kNoClock);
    return first;
  }
  // No clock read a frame: the room's echoes, perhaps. The equaliser models them on readings of
  // the packet at the nominal bit rate (sound cards are within a few tenths of a percent, and
  // the equaliser finds the sender's offset itself), from where the best clock put the break and
  // a few bits either side: a room's echoes make a clock a bit or two late, or a
  // few percent fast, explain the known bits best (in a measured teaching room at DRR 0 dB the
  // best clock was often 2 bits late or 2 % fast, and the equaliser read 23 of 60 packets on it,
  // 54 on these). The first reading whose frame passes is the packet. Deep noise misplaces the
  // best clock too: these readings also lifted white noise at -12 dB from 40 to 51 packets of
  // 60. Last, the best clock itself, for a sender whose card is off.
  struct Reading {
    std::int64_t at[kPacketBits];
    double rate_error;
    int shift_bits;  // from where the best clock put the break, at the nominal rate
    bool own_clock;  // or on the best clock itself
  };
  std::vector<Reading> readings;
  std::vector<int> shifts{0};  // bits
  for (int b = 1; b <= std::max(kEqualizerEarlyBits, kEqualizerLateBits); ++b) {
    if (b <= kEqualizerEarlyBits) shifts.push_back(-b);
    if (b <= kEqualizerLateBits) shifts.push_back(b);
  }
  const std::int64_t anchor = first_at[kBreakSpaceBits];  // the break's first MARK bit
  for (const int shift : shifts) {
    Reading r;
    r.rate_error = 0.0;
    r.shift_bits = shift;
    r.own_clock = false;
    for (int k = 0; k < kPacketBits; ++k) r.at[k] = anchor + std::llround((shift + k - kBreakSpaceBits) * per_bit_);
    readings.push_back(r);
  }
  if (std::abs(first.rate_error) > kEqualizerOwnClockRate) {
    Reading r;
    r.rate_error = first.rate_error;
    r.shift_bits = 0;
    r.own_clock = true;
    std::copy(first_at, first_at + kPacketBits, r.at);
    readings.push_back(r);
  }
  for (const Reading& r : readings) {
    const std::optional<RepairedFrame> repaired = Equalize(r.at, r.rate_error);
    if (trace != nullptr) trace->equalizer.push_back({r.shift_bits, r.own_clock, r.rate_error, repaired.has_value(), repaired ? repaired->fixed_bits : 0});
    if (!repaired) continue;
    first.kind = RxEvent::Kind::kPacket;
    first.noise = RxEvent::Noise::kNone;
    first.data.assign(repaired->frame.begin() + 1, repaired->frame.begin() + 1 + kDataBytes);
    first.fixed_bits = repaired->fixed_bits;
    // The packet's start, end and rate stay the best clock's: the equaliser's taps reach from a
    // bit early to 20 bits late, so the reading that passed places the packet no better (timing
    // the first arrival around it put two packets of a measured clap 8.5 ms late).
    break;
  }
  outcome(first.kind == RxEvent::Kind::kPacket ? BreakOutcome::kPacketByEqualizer : BreakOutcome::kNotRead);
  return first;
}

void FskReceiver::Outputs(const std::int64_t* at_step, std::complex<double> heard[2][kPacketBits], double* at) const {
  for (int k = 0; k < kPacketBits; ++k) {
    heard[0][k] = ring_.mark(at_step[k]);
    heard[1][k] = ring_.space(at_step[k]);
    at[k] = static_cast<double>(at_step[k]) * filters_.step();
  }
}

std::optional<RepairedFrame> FskReceiver::Equalize(const std::int64_t* at_step, double rate_error) const {
  std::complex<double> heard[2][kPacketBits];
  double at[kPacketBits];
  Outputs(at_step, heard, at);
  const std::complex<double>* const outputs[2] = {heard[0], heard[1]};
  std::optional<RepairedFrame> repaired;
  equalizer_.Equalize(outputs, at, rate_error, [&](const SoftFrame& soft, const ErrorEvents& events) {
    // One bit, then whole error events, never any two weak bits: the equaliser fits its taps to
    // the known header, so on its readings the header checks little and the CRC's 16 bits are
    // most of the check, spent on up to a dozen readings of up to four passes each. Two-bit
    // repairs of any pair of weak bits made 111 of the 120 wrong frames the equaliser's readings
    // passed (counted as in frame_repair.h) at SNR -10 to +5 dB over the measured rooms, and
    // its true two-bit errors are nearly all one event. A sequence search's errors come as
    // events: a competitor path that changes a few bits together (a transition moved by a bit).
    repaired = RepairFrame(soft, modem_.crc, std::min(options_.max_fixed_bits, 1));
    if (!repaired && options_.max_fixed_bits >= 2) {
      repaired = RepairEvent(soft, events, modem_.crc, kEventRepairs, kMaxEventBits);
    }
    return repaired.has_value();
  });
  return repaired;
}

}  // namespace nava_modem
