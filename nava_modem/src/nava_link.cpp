#include "nava_modem/nava_link.h"

#include "nava_modem/array_decode.h"
#include "nava_modem/frame.h"
#include "nava_modem/power_of_two.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nava_modem {
namespace {

// Audio moves to and from the device in blocks this long: short against the back-off and the
// deaf time, long enough that the system calls do not dominate.
constexpr double kBlockSeconds = 0.005;
// How long after a packet ends its receiver may report it (the room profile's matched filter
// works in blocks of up to a third of a second), and a little more.
constexpr double kDirectionMarginSeconds = 1.5;
// The longest a tick waits for the next try at reopening a failed device.
constexpr double kDownWaitSeconds = 0.05;
// A link behind its capture has caught up once it is within this share of max_capture_lag.
constexpr double kCaughtUpShare = 0.5;
// The longest (s of audio) a link behind its capture holds its sends: one that cannot catch up
// (a machine too slow for real time) sends on stale carrier sense rather than not at all.
constexpr double kLongestHoldSeconds = 2.0;

LinkOptions Checked(LinkOptions o, const AudioDevice& device) {
  if (std::abs(device.sample_rate() - o.modem.sample_rate) > 0.5) {
    throw std::invalid_argument("the audio device runs at " + std::to_string(device.sample_rate()) +
                                " Hz, the modem at " + std::to_string(o.modem.sample_rate) + " Hz");
  }
  const std::size_t channels = static_cast<std::size_t>(device.capture_channels());
  if (!o.microphones.empty() && o.microphones.size() != channels) {
    throw std::invalid_argument("the audio device captures " + std::to_string(channels) + " channels, but " +
                                std::to_string(o.microphones.size()) + " microphone positions were given (one per channel)");
  }
  UseProfileTiming(o.profile, o.modem, o.mac);
  ValidateLinkOptions(o);
  return o;
}

}  // namespace

void ValidateLinkOptions(const LinkOptions& o) {
  ValidateReceiverOptions(o.receiver);
  ValidateReopenOptions(o.reopen);
  if (!(o.max_capture_lag > 0.0 && o.max_capture_lag <= 10.0)) {
    throw std::invalid_argument("max capture lag " + std::to_string(o.max_capture_lag) + " s: expected above 0 and at most 10");
  }
  if (!(o.max_loop > 0.0 && o.max_loop <= 10.0)) {
    throw std::invalid_argument("max loop " + std::to_string(o.max_loop) + " s: expected above 0 and at most 10");
  }
}

NavaLink::NavaLink(const LinkOptions& options, AudioDevice& device, Clock& clock)
    : options_(Checked(options, device)),
      device_(device),
      profile_(MakeProfile(options_.profile, options_.modem)),
      receiver_(profile_->MakeReceiver(options_.receiver)),
      mac_(options_.mac, options_.seed),
      samples_per_tick_(mac_.tick_seconds() * options_.modem.sample_rate),
      block_(static_cast<std::size_t>(std::max(1.0, std::round(kBlockSeconds * options_.modem.sample_rate)))),
      channels_(static_cast<std::size_t>(device.capture_channels())),
      self_timer_(*profile_, options_.max_loop),
      clock_(clock),
      card_rate_(CardRateOptions{options_.modem.sample_rate}),
      reopen_(options_.reopen) {
  if (options_.microphones.size() >= 2) {
    estimator_ = std::make_unique<DirectionEstimator>(DirectionOptionsFor(options_.profile, options_.modem, options_.microphones));
    // A packet and what it takes the receiver to report it.
    const std::size_t size = PowerOfTwoAtLeast((profile_->Airtime() * 1.1 + kDirectionMarginSeconds) * options_.modem.sample_rate);
    history_.assign(channels_, std::vector<float>(size, 0.0f));
    history_mask_ = size - 1;
    span_.resize(channels_);
  }
}

bool NavaLink::Send(std::vector<std::uint8_t> data) {
  if (data.size() != static_cast<std::size_t>(kDataBytes)) {
    throw std::invalid_argument("a Nava packet carries 4 data bytes, got " + std::to_string(data.size()));
  }
  return mac_.Enqueue(std::move(data));
}

bool NavaLink::Tick(std::vector<RxEvent>& events) {
  if (device_down_) {
    TryReopen();
    return true;
  }
  try {
    return Run(events);
  } catch (const DeviceFault& e) {
    Fail(e.what(), events);
    return true;
  }
}

bool NavaLink::Run(std::vector<RxEvent>& events) {
  // Ticks are a whole number of samples on average: tick k ends at sample round((k+1) * s).
  const std::int64_t end = std::llround((ticks_ + 1) * samples_per_tick_);
  const std::size_t count = static_cast<std::size_t>(end - samples_done_);
  in_.resize(count);
  if (!Take(in_.data(), count)) return false;
  samples_done_ = end;
  ++ticks_;

  const MacState before = mac_.state();
  receiver_->SetMuted(before == MacState::kSending || before == MacState::kDeaf);
  const std::size_t first_new = events.size();
  receiver_->Process(in_.data(), count, events);
  if (estimator_) EstimateDirections(events, first_new);
  std::vector<OwnTiming> own;
  self_timer_.Heard(in_.data(), count, own);
  KeepOwnTimings(own);
  // The thesis's receiver threshold is the MAC's, known once calibration ends: from then on,
  // busy air with no packet is ZERO_BYTE noise.
  if (!threshold_shared_ && before != MacState::kCalibrating) {
    receiver_->SetCarrierThreshold(mac_.threshold_db());
    threshold_shared_ = true;
  }

  // Behind real time, carrier sense is stale: no send starts (for a while).
  const bool may_send = !behind_ || samples_done_ - behind_since_ > std::llround(kLongestHoldSeconds * options_.modem.sample_rate);
  if (std::optional<CsmaMac::Packet> packet = mac_.Tick(receiver_->level_db(), may_send)) {
    burst_ = profile_->ModulatePacket(*packet);
    if (options_.receiver.time_arrivals) self_timer_.Sent(*packet, time());
    // It starts with this tick's playback.
    in_flight_.push_back({std::move(*packet), queued_out_ + static_cast<std::int64_t>(burst_.size())});
    burst_at_ = 0;
    burst_cut_ = false;
    burst_written_ = 0;
  }
  // Playback runs in step with capture: this tick's share of the burst, or silence.
  std::vector<float>& out = in_;
  std::fill(out.begin(), out.end(), 0.0f);
  if (burst_at_ < burst_.size()) {
    const std::size_t n = std::min(count, burst_.size() - burst_at_);
    std::copy(burst_.begin() + burst_at_, burst_.begin() + burst_at_ + n, out.begin());
    burst_at_ += n;
    burst_pending_ += n;
  } else if (behind_ && playing_.size() + count > device_.PlaybackRoom()) {
    // The process stalled and the device kept what it captured meanwhile: silence is played
    // only where it needs no wait (what waits to play goes now), so that the link runs faster
    // than real time until it has heard the backlog. No captured sound is lost.
    if (!playing_.empty() && playing_.size() <= device_.PlaybackRoom()) Write();
    return true;
  }
  Put(out.data(), count);
  return true;
}

bool NavaLink::Take(float* out, std::size_t count) {
  while (captured_.size() - captured_at_ < count) {
    // Whole blocks from the device: a system call per tick would cost more than the modem.
    captured_.erase(captured_.begin(), captured_.begin() + static_cast<std::ptrdiff_t>(captured_at_));
    captured_at_ = 0;
    frames_.resize(block_ * channels_);
    if (!device_.Read(frames_.data(), block_)) return false;
    // The receiver hears the first microphone: summing a small array's channels, each a little
    // delayed, would comb-filter the band; the others are kept for the direction.
    for (std::size_t f = 0; f < block_; ++f) {
      captured_.push_back(frames_[f * channels_]);
      if (!history_.empty()) {
        const std::size_t at = static_cast<std::size_t>(frames_read_ + static_cast<std::int64_t>(f)) & history_mask_;
        for (std::size_t c = 0; c < channels_; ++c) history_[c][at] = frames_[f * channels_ + c];
      }
    }
    frames_read_ += static_cast<std::int64_t>(block_);
    card_frames_ += static_cast<std::int64_t>(block_);
    const std::size_t waiting = device_.CaptureLag();  // one query of the device a block
    card_rate_.Add(clock_.Now(), card_frames_ + static_cast<std::int64_t>(waiting));
    const double lag = static_cast<double>(waiting) / options_.modem.sample_rate;
    if (!behind_ && lag > options_.max_capture_lag) {
      behind_ = true;
      behind_since_ = samples_done_;
      ++catch_ups_;
    } else if (behind_ && lag <= kCaughtUpShare * options_.max_capture_lag) {
      behind_ = false;
    }
  }
  std::copy(captured_.begin() + captured_at_, captured_.begin() + captured_at_ + count, out);
  captured_at_ += count;
  return true;
}

void NavaLink::EstimateDirections(std::vector<RxEvent>& events, std::size_t first) {
  const double rate = options_.modem.sample_rate;
  const std::int64_t oldest = frames_read_ - static_cast<std::int64_t>(history_mask_);
  for (std::size_t k = first; k < events.size(); ++k) {
    RxEvent& e = events[k];
    const std::int64_t from = std::max<std::int64_t>(oldest, std::llround(e.start * rate));
    const std::int64_t to = std::min<std::int64_t>(frames_read_, std::llround(e.end * rate));
    if (to - from < 64) continue;  // too little of it left to tell
    std::vector<const float*> channels;
    for (std::size_t c = 0; c < channels_; ++c) {
      span_[c].resize(static_cast<std::size_t>(to - from));
      for (std::int64_t n = from; n < to; ++n) span_[c][static_cast<std::size_t>(n - from)] = history_[c][static_cast<std::size_t>(n) & history_mask_];
      channels.push_back(span_[c].data());
    }
    const Direction d = estimator_->Estimate(channels, static_cast<std::size_t>(to - from));
    e.direction = d.bearing;
    e.direction_confidence = std::isfinite(d.bearing) ? d.confidence : 0.0;
  }
}

void NavaLink::Put(const float* in, std::size_t count) {
  queued_out_ += static_cast<std::int64_t>(count);
  playing_.insert(playing_.end(), in, in + count);
  if (playing_.size() >= block_) Write();
}

void NavaLink::Write() {
  device_.Write(playing_.data(), playing_.size());
  written_ += static_cast<std::int64_t>(playing_.size());
  playing_.clear();
  played_ = std::max(played_, written_ - static_cast<std::int64_t>(device_.PlaybackDelay()));
  while (!in_flight_.empty() && in_flight_.front().end <= played_) in_flight_.pop_front();
  // An underrun met by this write left a gap before its samples: inside the packet when some
  // of it went out before and some goes out now.
  if (device_.underruns() != underruns_seen_) {
    underruns_seen_ = device_.underruns();
    if (burst_written_ > 0 && burst_pending_ > 0 && !burst_cut_) {
      burst_cut_ = true;
      ++packets_cut_;
    }
  }
  burst_written_ += burst_pending_;
  burst_pending_ = 0;
}

// The device failed: what it had not played of the packets sent goes again, and what was heard
// is decoded to its end.
void NavaLink::Fail(const std::string& error, std::vector<RxEvent>& events) {
  ++device_faults_;
  device_error_ = error;
  device_down_ = true;
  card_rate_.Reset();  // the reopened device's frames count from 0
  card_frames_ = 0;
  // The playback position is known as of the last write: a packet whose end played after it
  // goes again (listeners that lost the same sound server most likely missed that end too).
  std::vector<CsmaMac::Packet> unsent;
  for (InFlight& f : in_flight_) unsent.push_back(std::move(f.data));
  in_flight_.clear();
  mac_.Interrupt(std::move(unsent), options_.reopen.settle_time);
  burst_.clear();
  burst_at_ = 0;
  burst_cut_ = false;
  burst_written_ = burst_pending_ = 0;
  playing_.clear();
  queued_out_ = written_ = played_ = 0;
  behind_ = false;
  EndHearing(events);
  reopen_.Start(clock_.Now());
}

// The audio heard before a failure is decoded as if silence followed: a packet that had just
// ended is reported now, one cut short ends as noise or nothing, and the audio after the
// reopen begins nothing half-heard. The receiver's clock (and the microphones' history, which
// follows it) moves past that silence.
void NavaLink::EndHearing(std::vector<RxEvent>& events) {
  const std::size_t first = events.size();
  const double rate = options_.modem.sample_rate;
  const std::size_t unheard = captured_.size() - captured_at_;
  receiver_->Process(captured_.data() + captured_at_, unheard, events);
  std::vector<OwnTiming> own;
  self_timer_.Heard(captured_.data() + captured_at_, unheard, own);
  captured_.clear();
  captured_at_ = 0;
  const double before = receiver_->time();
  receiver_->Flush(events);
  const std::int64_t silence = std::llround((receiver_->time() - before) * rate);
  if (!history_.empty()) {
    for (std::int64_t n = frames_read_; n < frames_read_ + silence; ++n) {
      for (std::vector<float>& channel : history_) channel[static_cast<std::size_t>(n) & history_mask_] = 0.0f;
    }
  }
  frames_read_ += silence;
  samples_flushed_ += static_cast<std::int64_t>(unheard) + silence;
  self_timer_.Skip(static_cast<double>(silence) / rate, own);
  KeepOwnTimings(own);
  if (estimator_) EstimateDirections(events, first);
}

void NavaLink::TryReopen() {
  const double now = clock_.Now();
  if (now < reopen_.next_try()) {
    clock_.Sleep(std::min(reopen_.next_try() - now, kDownWaitSeconds));
    return;
  }
  try {
    device_.Reopen();
  } catch (const DeviceFault& e) {
    device_error_ = e.what();
    reopen_.Failed(clock_.Now());
    return;
  }
  device_down_ = false;
  ++reopens_;
  underruns_seen_ = device_.underruns();
}

void NavaLink::KeepOwnTimings(std::vector<OwnTiming>& fresh) {
  for (OwnTiming& t : fresh) own_timings_.push_back(std::move(t));
  if (own_timings_.size() > kMaxOwnTimings) {
    const std::size_t extra = own_timings_.size() - kMaxOwnTimings;
    own_timings_.erase(own_timings_.begin(), own_timings_.begin() + static_cast<std::ptrdiff_t>(extra));
    own_timings_dropped_ += extra;
  }
}

std::vector<OwnTiming> NavaLink::TakeOwnTimings() {
  std::vector<OwnTiming> out;
  out.swap(own_timings_);
  return out;
}

}  // namespace nava_modem
