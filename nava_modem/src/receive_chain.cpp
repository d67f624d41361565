#include "nava_modem/receive_chain.h"

#include <algorithm>
#include <cmath>

#include "nava_modem/array_decode.h"

namespace nava_modem {
namespace {

// How long after a packet ends its receiver may report it (the room profile's matched filter
// works in blocks of up to a third of a second), and a little more.
constexpr double kDirectionMarginSeconds = 1.5;
// Fewer samples of a reception than this left in the history tell no direction.
constexpr std::int64_t kShortestSpan = 64;

}  // namespace

ReceiveChain::ReceiveChain(const ModemProfile& profile, const ReceiveChainOptions& options)
    : profile_(profile),
      options_(options),
      sample_rate_(profile.options().sample_rate),
      receiver_(profile.MakeReceiver(options.receiver)),
      self_timer_(profile, options.max_loop) {
  if (options_.microphones.size() >= 2) {
    estimator_ = std::make_unique<DirectionEstimator>(DirectionOptionsFor(profile.profile(), profile.options(), options_.microphones));
  }
}

double ReceiveChain::history_seconds() const {
  return estimator_ ? profile_.Airtime() * 1.1 + kDirectionMarginSeconds : 0.0;
}

void ReceiveChain::Hear(const float* samples, std::size_t count, bool muted, std::vector<RxEvent>& events,
                        const CaptureHistory* history) {
  receiver_->SetMuted(muted);
  const std::size_t first = events.size();
  receiver_->Process(samples, count, events);
  EstimateDirections(events, first, history);
  std::vector<OwnTiming> own;
  self_timer_.Heard(samples, count, own);
  KeepOwnTimings(own);
}

void ReceiveChain::Sent(const std::vector<std::uint8_t>& data, double time) {
  if (options_.receiver.time_arrivals) self_timer_.Sent(data, time);
}

void ReceiveChain::ShareCarrierThreshold(double db) {
  if (threshold_shared_) return;
  receiver_->SetCarrierThreshold(db);
  threshold_shared_ = true;
}

std::int64_t ReceiveChain::EndHearing(const float* unheard, std::size_t count, std::vector<RxEvent>& events,
                                      CaptureHistory* history) {
  const std::size_t first = events.size();
  receiver_->Process(unheard, count, events);
  std::vector<OwnTiming> own;
  self_timer_.Heard(unheard, count, own);
  const double before = receiver_->time();
  receiver_->Flush(events);
  // The receiver's clock, and the microphones' history that follows it, move past that silence.
  const std::int64_t silence = std::llround((receiver_->time() - before) * sample_rate_);
  if (history) history->RecordSilence(silence);
  self_timer_.Skip(static_cast<double>(silence) / sample_rate_, own);
  KeepOwnTimings(own);
  EstimateDirections(events, first, history);
  return silence;
}

void ReceiveChain::EstimateDirections(std::vector<RxEvent>& events, std::size_t first, const CaptureHistory* history) {
  if (!estimator_ || !history) return;
  for (std::size_t k = first; k < events.size(); ++k) {
    RxEvent& e = events[k];
    const std::int64_t from = std::max<std::int64_t>(history->oldest(), std::llround(e.start * sample_rate_));
    const std::int64_t to = std::min<std::int64_t>(history->end(), std::llround(e.end * sample_rate_));
    if (to - from < kShortestSpan) continue;  // too little of it left to tell
    history->Copy(from, to, span_);
    std::vector<const float*> channels;
    for (const std::vector<float>& c : span_) channels.push_back(c.data());
    const Direction d = estimator_->Estimate(channels, static_cast<std::size_t>(to - from));
    e.direction = d.bearing;
    e.direction_confidence = std::isfinite(d.bearing) ? d.confidence : 0.0;
  }
}

void ReceiveChain::KeepOwnTimings(std::vector<OwnTiming>& fresh) {
  for (OwnTiming& t : fresh) own_timings_.push_back(std::move(t));
  if (own_timings_.size() > kMaxOwnTimings) {
    const std::size_t extra = own_timings_.size() - kMaxOwnTimings;
    own_timings_.erase(own_timings_.begin(), own_timings_.begin() + static_cast<std::ptrdiff_t>(extra));
    own_timings_dropped_ += extra;
  }
}

std::vector<OwnTiming> ReceiveChain::TakeOwnTimings() {
  std::vector<OwnTiming> out;
  out.swap(own_timings_);
  return out;
}

}  // namespace nava_modem
