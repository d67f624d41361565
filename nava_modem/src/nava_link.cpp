#include "nava_modem/nava_link.h"


#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nava_modem {
namespace {

// Audio moves to and from the device in blocks this long: short against the back-off and the
// deaf time, long enough that the system calls do not dominate.
constexpr double kBlockSeconds = 0.005;
// The longest a tick waits for the next try at reopening a failed device.
constexpr double kDownWaitSeconds = 0.05;
// The longest (s of audio) a link behind its capture holds its sends: one that cannot catch up
// (a machine too slow for real time) sends on stale carrier sense rather than not at all.
constexpr double kLongestHoldSeconds = 2.0;

std::size_t BlockFrames(double sample_rate) {
  return static_cast<std::size_t>(std::max(1.0, std::round(kBlockSeconds * sample_rate)));
}

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
  const int rates = ProfileFormat(o.profile).rates;
  if (o.rate < 0 || o.rate >= rates) {
    throw std::invalid_argument("rate " + std::to_string(o.rate) + ": profile " + ProfileName(o.profile) +
                                " has rates 0 to " + std::to_string(rates - 1));
  }
}

NavaLink::NavaLink(const LinkOptions& options, AudioDevice& device, Clock& clock)
    : options_(Checked(options, device)),
      device_(device),
      clock_(clock),
      profile_(MakeProfile(options_.profile, options_.modem)),
      mac_(options_.mac, options_.seed),
      receive_(*profile_, ReceiveChainOptions{options_.receiver, options_.microphones, options_.max_loop}),
      capture_(CaptureOptions{options_.modem.sample_rate, BlockFrames(options_.modem.sample_rate), options_.max_capture_lag,
                              receive_.history_seconds()},
               device, clock),
      playback_(device, BlockFrames(options_.modem.sample_rate)),
      samples_per_tick_(mac_.tick_seconds() * options_.modem.sample_rate),
      reopen_(options_.reopen) {}

bool NavaLink::Send(std::vector<std::uint8_t> data) { return Send(std::move(data), options_.rate); }

bool NavaLink::Send(std::vector<std::uint8_t> data, int rate) {
  const double airtime = profile_->Airtime(data.size(), rate);  // CheckFrame's errors
  return mac_.Enqueue(MacFrame{std::move(data), rate, airtime});
}

bool NavaLink::Tick(std::vector<RxEvent>& events) {
  if (device_down_) {
    TryReopen();
    return true;
  }
  const std::size_t first = events.size();
  bool more = true;
  try {
    more = Run(events);
  } catch (const DeviceFault& e) {
    Fail(e.what(), events);
  }
  for (std::size_t k = first; k < events.size(); ++k) heard_.Add(events[k]);
  return more;
}

LinkStatus NavaLink::status() const {
  LinkStatus s;
  s.state = mac_.state();
  s.threshold_db = mac_.threshold_db();
  s.level_db = level_db();
  s.sent = packets_sent();
  s.queue_drops = mac_.dropped();
  s.heard = heard_;
  s.overruns = overruns();
  s.underruns = underruns();
  s.packets_cut = packets_cut();
  s.catch_ups = catch_ups();
  s.device_down = device_down_;
  s.device_error = device_error_;
  s.device_faults = device_faults_;
  s.reopens = reopens_;
  s.requeued = packets_requeued();
  s.failed_reopens = failed_reopens();
  return s;
}

bool NavaLink::Run(std::vector<RxEvent>& events) {
  // Ticks are a whole number of samples on average: tick k ends at sample round((k+1) * s).
  const std::int64_t end = std::llround((ticks_ + 1) * samples_per_tick_);
  const std::size_t count = static_cast<std::size_t>(end - samples_done_);
  in_.resize(count);
  if (!capture_.Take(in_.data(), count, samples_done_)) return false;
  samples_done_ = end;
  ++ticks_;

  const MacState before = mac_.state();
  receive_.Hear(in_.data(), count, before == MacState::kSending || before == MacState::kDeaf, events, capture_.history());
  if (before != MacState::kCalibrating) receive_.ShareCarrierThreshold(mac_.threshold_db());

  // Behind real time, carrier sense is stale: no send starts (for a while).
  const bool may_send = !capture_.behind() ||
                        samples_done_ - capture_.behind_since() > std::llround(kLongestHoldSeconds * options_.modem.sample_rate);
  if (std::optional<MacFrame> frame = mac_.Tick(receive_.level_db(), may_send)) {
    receive_.Sent(frame->data, time());
    // It starts with this tick's playback.
    std::vector<float> sound = profile_->Modulate(frame->data, frame->rate);
    playback_.Start(std::move(*frame), std::move(sound));
  }
  // Playback runs in step with capture: this tick's share of the packet, or silence.
  playback_.Tick(count, capture_.behind());
  return true;
}

// The device failed: each part starts over. What it had not played of the packets sent goes
// again (the playback position is known as of the last write), and what was heard is decoded
// to its end.
void NavaLink::Fail(const std::string& error, std::vector<RxEvent>& events) {
  ++device_faults_;
  device_error_ = error;
  device_down_ = true;
  mac_.Interrupt(playback_.Abort(), options_.reopen.settle_time);
  const std::size_t unheard = capture_.unheard_count();
  const std::int64_t silence = receive_.EndHearing(capture_.unheard(), unheard, events, capture_.history());
  samples_flushed_ += static_cast<std::int64_t>(unheard) + silence;
  capture_.Reset();
  reopen_.Start(clock_.Now());
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
  playback_.Reopened();
}

}  // namespace nava_modem
