#include "nava_modem/link_playback.h"

#include <algorithm>

namespace nava_modem {

LinkPlayback::LinkPlayback(AudioDevice& device, std::size_t block) : device_(device), block_(block) {}

void LinkPlayback::Start(MacFrame packet, std::vector<float> sound) {
  burst_ = std::move(sound);
  in_flight_.push_back({std::move(packet), queued_out_ + static_cast<std::int64_t>(burst_.size())});
  burst_at_ = 0;
  burst_cut_ = false;
  burst_written_ = 0;
}

void LinkPlayback::Tick(std::size_t count, bool behind) {
  out_.assign(count, 0.0f);
  if (burst_at_ < burst_.size()) {
    const std::size_t n = std::min(count, burst_.size() - burst_at_);
    std::copy(burst_.begin() + burst_at_, burst_.begin() + burst_at_ + n, out_.begin());
    burst_at_ += n;
    burst_pending_ += n;
  } else if (behind && playing_.size() + count > device_.PlaybackRoom()) {
    if (!playing_.empty() && playing_.size() <= device_.PlaybackRoom()) Write();
    return;
  }
  Put(out_.data(), count);
}

void LinkPlayback::Put(const float* samples, std::size_t count) {
  queued_out_ += static_cast<std::int64_t>(count);
  playing_.insert(playing_.end(), samples, samples + count);
  if (playing_.size() >= block_) Write();
}

void LinkPlayback::Write() {
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

std::vector<MacFrame> LinkPlayback::Abort() {
  // Listeners that lost the same sound server most likely missed a packet's end too.
  std::vector<MacFrame> unsent;
  for (InFlight& f : in_flight_) unsent.push_back(std::move(f.data));
  in_flight_.clear();
  burst_.clear();
  burst_at_ = 0;
  burst_cut_ = false;
  burst_written_ = burst_pending_ = 0;
  playing_.clear();
  queued_out_ = written_ = played_ = 0;
  return unsent;
}

}  // namespace nava_modem
