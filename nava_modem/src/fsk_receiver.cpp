#include "nava_modem/fsk_receiver.h"

#include <algorithm>
#include <cmath>

namespace nava_modem {
namespace {

constexpr double kTiny = 1e-20;
// Per-sample in-band power below which the break detector sees silence (-70 dB of full scale):
// the ratios it takes are meaningless on digital silence.
constexpr double kSilence = 1e-7;
constexpr int kDetectorBits = 10;  // each half of the break detector
// After the detector first passes its threshold, the strongest step within this many bits is
// taken as the break: noise can pass the threshold just before a real break arrives.
constexpr int kPeakWindowBits = 10;
// A step this much clearer than the break being collected replaces it. Real breaks are far
// clearer than noise (0.55 at -12 dB against at most 0.5 in noise alone); the MARK-then-SPACE
// patterns that data can hold are not.
constexpr double kSupersede = 0.2;
// Bit indices relative to the first MARK bit of the break.
constexpr int kFirstBit = -kBreakSpaceBits;
constexpr int kFrameStart = kBreakMarkBits;
constexpr int kEndBit = kBreakMarkBits + kFrameBits;
// The bit clock's loop gains: small, because the fit over the whole packet already has the
// clock right to a few hundredths of a bit; the loop only follows what a straight line cannot
// (a resampler's wander).
constexpr double kPhaseGain = 0.1;
constexpr double kPeriodGain = 0.002;
// Bit clocks tried per packet (see DecodeFrame).
constexpr std::size_t kClockHypotheses = 3;
// Crossings are trusted for the loop only between bits decided at least this clearly.
constexpr double kLoopMinSoft = 0.3;

// The MARK and SPACE filter outputs summed (the thesis's quality figure), from the difference d
// and the sum e of their squares.
double FilterSum(double d, double e) {
  return std::sqrt(std::max(0.0, (e + d) / 2.0)) + std::sqrt(std::max(0.0, (e - d) / 2.0));
}

// The value a bit is known to have, or -1 where the packet's content decides.
int KnownBit(int k) {
  if (k < 0) return 0;            // the break's SPACE half
  if (k < kFrameStart) return 1;  // its MARK half
  const int j = k - kFrameStart, pos = j % kBitsPerByte, byte = j / kBitsPerByte;
  if (pos == 0) return 0;  // start bit
  if (pos == 9) return 1;  // stop bit
  if (byte == 0) return (kHeader >> (pos - 1)) & 1;
  return -1;
}

std::size_t RingSize(double per_bit) {
  const double needed = 150.0 * per_bit + 64.0;
  std::size_t size = 1;
  while (size < needed) size <<= 1;
  return size;
}

}  // namespace

FskReceiver::FskReceiver(const ModemOptions& modem, const ReceiverOptions& options)
    : modem_(modem), options_(options), filters_(modem),
      per_bit_(SamplesPerBit(modem) / filters_.step()), seconds_per_step_(filters_.step() / modem.sample_rate) {
  ValidateModemOptions(modem_);
  w_ = static_cast<std::int64_t>(std::lround(kDetectorBits * per_bit_));
  const std::size_t size = RingSize(per_bit_);
  d_.assign(size, 0.0f);
  e_.assign(size, 0.0f);
  mask_ = size - 1;
  SetCarrierThreshold(options_.carrier_threshold_db);
}

void FskReceiver::SetCarrierThreshold(std::optional<double> db) {
  options_.carrier_threshold_db = db;
  if (db) carrier_threshold_power_ = std::pow(10.0, *db / 10.0);
}

double FskReceiver::level_db() const { return 10.0 * std::log10(E(n_ - 1) + kTiny); }

void FskReceiver::SetMuted(bool muted) {
  if (muted && !muted_) {
    state_ = State::kSearching;
    busy_ = false;
  }
  if (!muted && muted_) blank_until_ = std::max(blank_until_, n_ + 2 * w_);
  muted_ = muted;
}

void FskReceiver::Process(const float* samples, std::size_t count, std::vector<RxEvent>& events) {
  for (std::size_t k = 0; k < count; ++k) {
    if (filters_.Push(samples[k])) Step(events);
  }
}

void FskReceiver::Flush(std::vector<RxEvent>& events) {
  const std::size_t tail = filters_.step() * (static_cast<std::size_t>(std::ceil((kEndBit + 4) * per_bit_ * (1.0 + options_.max_rate_error))) +
                                               static_cast<std::size_t>(2 * w_));
  const std::vector<float> silence(tail, 0.0f);
  Process(silence.data(), silence.size(), events);
}

void FskReceiver::Step(std::vector<RxEvent>& events) {
  const double m2 = filters_.mark_power(), s2 = filters_.space_power();
  const double d = m2 - s2, e = m2 + s2;
  const std::int64_t n = n_;
  d_[n & mask_] = static_cast<float>(d);
  e_[n & mask_] = static_cast<float>(e);
  // The break detector's running sums over the last w samples and the w before them.
  after_ += d - D(n - w_);
  before_ += D(n - w_) - D(n - 2 * w_);
  after_power_ += e - E(n - w_);
  before_power_ += E(n - w_) - E(n - 2 * w_);
  ++n_;
  if ((n & 0xFFFF) == 0) {  // renew the running sums against rounding
    after_ = before_ = after_power_ = before_power_ = 0.0;
    for (std::int64_t k = n - 2 * w_ + 1; k <= n; ++k) {
      (k > n - w_ ? after_ : before_) += D(k);
      (k > n - w_ ? after_power_ : before_power_) += E(k);
    }
  }
  if (muted_) return;
  TrackCarrier(e, events);
  if (n < 2 * w_) return;
  // How much the last w samples are MARK and the w before them SPACE, each from -1 to 1; the
  // step is the smaller, so that the edge of a burst (tones on one side only) is no step.
  const double floor = kSilence * w_;
  const double step = std::min(after_ / std::max(after_power_, floor), -before_ / std::max(before_power_, floor));

  switch (state_) {
    case State::kSearching:
      if (n >= blank_until_ && step > options_.detect_threshold) {
        state_ = State::kPeaking;
        peak_ = step;
        peak_at_ = n;
      }
      break;
    case State::kPeaking:
      if (step > peak_) {
        peak_ = step;
        peak_at_ = n;
      } else if (n - peak_at_ > kPeakWindowBits * per_bit_) {
        // The windows' boundary sits on the filters' zero crossing, which lags the step by
        // half a window.
        break_step_ = peak_at_ - w_ - filters_.window() / 2.0 + 1.5;
        decode_at_ = static_cast<std::int64_t>(std::ceil(break_step_ + (kEndBit + 1) * per_bit_ * (1.0 + options_.max_rate_error) + per_bit_));
        state_ = State::kCollecting;
      }
      break;
    case State::kCollecting:
      if (step > peak_ + kSupersede) {
        // A much clearer break than the one being collected: that one was noise.
        state_ = State::kPeaking;
        peak_ = step;
        peak_at_ = n;
      } else if (n >= decode_at_) {
        events.push_back(DecodeFrame(break_step_));
        events.back().clarity = peak_;
        if (busy_) busy_had_frame_ = true;
        // No new break before the detector's windows have left this packet: its tail
        // followed by silence could pass for a step.
        blank_until_ = static_cast<std::int64_t>(events.back().end / seconds_per_step_) + 2 * w_;
        state_ = State::kSearching;
      }
      break;
  }
}

void FskReceiver::TrackCarrier(double e, std::vector<RxEvent>& events) {
  if (!options_.carrier_threshold_db) return;
  const bool loud = e >= carrier_threshold_power_;
  const std::int64_t n = n_ - 1;
  if (loud) {
    if (!busy_) {
      busy_ = true;
      busy_had_frame_ = false;
      busy_start_ = n;
      busy_power_ = busy_quality_ = 0.0;
      busy_samples_ = 0;
    }
    quiet_run_ = 0;
  } else if (busy_) {
    ++quiet_run_;
  }
  if (!busy_) return;
  busy_power_ += e;
  busy_quality_ += FilterSum(D(n), e);
  ++busy_samples_;
  // Busy air ends after a bit of quiet; a frame being decoded is waited for.
  if (quiet_run_ > per_bit_ && state_ == State::kSearching) {
    const std::int64_t end = n - quiet_run_;
    if (!busy_had_frame_ && end - busy_start_ >= per_bit_) {
      RxEvent ev;
      ev.kind = RxEvent::Kind::kNoise;
      ev.noise = RxEvent::Noise::kZeroByte;
      ev.start = Seconds(static_cast<double>(busy_start_));
      ev.end = Seconds(static_cast<double>(end));
      ev.level_db = 10.0 * std::log10(busy_power_ / busy_samples_ + kTiny);
      ev.quality = busy_quality_ / busy_samples_;
      events.push_back(ev);
    }
    busy_ = false;
  }
}

double FskReceiver::FitMetric(double first_mark, double period) const {
  double sum = 0.0;
  for (int k = kFirstBit; k < kEndBit; ++k) {
    const double v = D(std::llround(first_mark + (k + 1) * period - 1.0));
    const int known = KnownBit(k);
    sum += known < 0 ? std::abs(v) : (known ? v : -v);
  }
  return sum;
}

FskReceiver::ClockFit FskReceiver::BestFit(double start0, double period0, double phase_span, double phase_step,
                                           double rate_span, double rate_step) const {
  ClockFit best{start0, period0, -1e300};
  for (double r = -rate_span; r <= rate_span + 1e-12; r += rate_step) {
    const double period = period0 * (1.0 + r);
    for (double p = -phase_span; p <= phase_span + 1e-9; p += phase_step) {
      const double metric = FitMetric(start0 + p, period);
      if (metric > best.metric) best = {start0 + p, period, metric};
    }
  }
  return best;
}

RxEvent FskReceiver::DecodeFrame(double break_step) {
  // The bit clock that best explains the packet's known bits and the strength of its unknown
  // ones, over a grid of phases for each rate. In deep noise the best fit can be a wrong one,
  // so the best few rates that are local optima are each refined on a finer grid and read in
  // turn; the first whose frame checks is the packet.
  const double rate_step = 0.0025;
  const int rates = static_cast<int>(std::lround(options_.max_rate_error / rate_step));
  std::vector<ClockFit> per_rate;
  for (int k = -rates; k <= rates; ++k) {
    per_rate.push_back(BestFit(break_step, per_bit_ * (1.0 + k * rate_step), per_bit_ / 2.0, per_bit_ / 16.0, 0.0, 1.0));
  }
  std::vector<ClockFit> candidates;
  for (std::size_t k = 0; k < per_rate.size(); ++k) {
    const bool left = k == 0 || per_rate[k].metric >= per_rate[k - 1].metric;
    const bool right = k + 1 == per_rate.size() || per_rate[k].metric >= per_rate[k + 1].metric;
    if (left && right) candidates.push_back(per_rate[k]);
  }
  std::sort(candidates.begin(), candidates.end(), [](const ClockFit& a, const ClockFit& b) { return a.metric > b.metric; });
  if (candidates.size() > kClockHypotheses) candidates.resize(kClockHypotheses);
  RxEvent first;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const ClockFit fine = BestFit(candidates[k].start, candidates[k].period, per_bit_ / 16.0, per_bit_ / 64.0, rate_step, 0.0005);
    RxEvent ev = ReadFrame(fine.start, fine.period);
    if (ev.kind == RxEvent::Kind::kPacket) return ev;
    if (k == 0) first = ev;
  }
  return first;
}

RxEvent FskReceiver::ReadFrame(double best_start, double best_period) {
  BitClock clock(best_start, best_period, filters_.window(), kPhaseGain, kPeriodGain);
  SoftFrame soft{};
  std::uint8_t hard[kFrameBits];
  double power = 0.0, quality = 0.0;
  int previous = 1;  // the break's last bit is MARK
  double previous_soft = 1.0;
  for (int k = kFrameStart; k < kEndBit; ++k) {
    const std::int64_t at = std::llround(clock.AlignedSample(k));
    const double d = D(at), e = E(at);
    const double v = d / (e + kTiny);
    const int j = k - kFrameStart, pos = j % kBitsPerByte;
    hard[j] = v > 0.0;
    if (pos >= 1 && pos <= 8) soft[(j / kBitsPerByte) * 8 + pos - 1] = static_cast<float>(v);
    power += e;
    quality += FilterSum(d, e);
    // Follow the transition into this bit, if it is clear on both sides.
    if (hard[j] != previous && std::abs(v) > kLoopMinSoft && std::abs(previous_soft) > kLoopMinSoft) {
      const double expected = clock.ExpectedCrossing(k);
      const std::int64_t lo = std::llround(expected - clock.period() / 4.0);
      const std::int64_t hi = std::llround(expected + clock.period() / 4.0);
      double crossing = 0.0, nearest = 1e300;
      for (std::int64_t i = lo + 1; i <= hi; ++i) {
        const double a = D(i - 1), b = D(i);
        if ((a > 0.0) == (b > 0.0) || a == b) continue;
        const double at_zero = (i - 1) + a / (a - b);
        if (std::abs(at_zero - expected) < nearest) {
          nearest = std::abs(at_zero - expected);
          crossing = at_zero;
        }
      }
      if (nearest < 1e300) clock.Observe(k, crossing);
    }
    previous = hard[j];
    previous_soft = v;
  }

  RxEvent ev;
  ev.start = Seconds(best_start - kBreakSpaceBits * best_period);
  ev.end = Seconds(clock.Start(kEndBit));
  ev.level_db = 10.0 * std::log10(power / kFrameBits + kTiny);
  ev.quality = quality / kFrameBits;
  ev.rate_error = per_bit_ / best_period - 1.0;
  const std::optional<RepairedFrame> repaired = RepairFrame(soft, modem_.crc, options_.max_fixed_bits);
  if (repaired) {
    ev.kind = RxEvent::Kind::kPacket;
    ev.data.assign(repaired->frame.begin() + 1, repaired->frame.begin() + 1 + kDataBytes);
    ev.fixed_bits = repaired->fixed_bits;
    return ev;
  }
  ev.kind = RxEvent::Kind::kNoise;
  bool any_framed = false;
  for (int c = 0; c < kFrameBytes; ++c) any_framed = any_framed || ReadUartByte(hard + c * kBitsPerByte).framed;
  const UartByte header = ReadUartByte(hard);
  if (!any_framed) {
    ev.noise = RxEvent::Noise::kZeroByte;
  } else if (!header.framed || header.value != kHeader) {
    ev.noise = RxEvent::Noise::kOneByte;
  } else {
    ev.noise = RxEvent::Noise::kBadCrc;
  }
  return ev;
}

}  // namespace nava_modem
