#include "nava_modem/nava_link.h"

#include "nava_modem/frame.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nava_modem {
namespace {

// Audio moves to and from the device in blocks this long: short against the back-off and the
// deaf time, long enough that the system calls do not dominate.
constexpr double kBlockSeconds = 0.005;

LinkOptions Checked(LinkOptions o, const AudioDevice& device) {
  if (std::abs(device.sample_rate() - o.modem.sample_rate) > 0.5) {
    throw std::invalid_argument("the audio device runs at " + std::to_string(device.sample_rate()) +
                                " Hz, the modem at " + std::to_string(o.modem.sample_rate) + " Hz");
  }
  UseProfileTiming(o.profile, o.modem, o.mac);
  return o;
}

}  // namespace

NavaLink::NavaLink(const LinkOptions& options, AudioDevice& device)
    : options_(Checked(options, device)),
      device_(device),
      profile_(MakeProfile(options_.profile, options_.modem)),
      receiver_(profile_->MakeReceiver(options_.receiver)),
      mac_(options_.mac, options_.seed),
      samples_per_tick_(mac_.tick_seconds() * options_.modem.sample_rate),
      block_(static_cast<std::size_t>(std::max(1.0, std::round(kBlockSeconds * options_.modem.sample_rate)))) {}

bool NavaLink::Send(std::vector<std::uint8_t> data) {
  if (data.size() != static_cast<std::size_t>(kDataBytes)) {
    throw std::invalid_argument("a Nava packet carries 4 data bytes, got " + std::to_string(data.size()));
  }
  return mac_.Enqueue(std::move(data));
}

bool NavaLink::Tick(std::vector<RxEvent>& events) {
  // Ticks are a whole number of samples on average: tick k ends at sample round((k+1) * s).
  const std::int64_t end = std::llround((ticks_ + 1) * samples_per_tick_);
  const std::size_t count = static_cast<std::size_t>(end - samples_done_);
  in_.resize(count);
  if (!Take(in_.data(), count)) return false;
  samples_done_ = end;
  ++ticks_;

  const MacState before = mac_.state();
  receiver_->SetMuted(before == MacState::kSending || before == MacState::kDeaf);
  receiver_->Process(in_.data(), count, events);
  // The thesis's receiver threshold is the MAC's, known once calibration ends: from then on,
  // busy air with no packet is ZERO_BYTE noise.
  if (!threshold_shared_ && before != MacState::kCalibrating) {
    receiver_->SetCarrierThreshold(mac_.threshold_db());
    threshold_shared_ = true;
  }

  if (std::optional<CsmaMac::Packet> packet = mac_.Tick(receiver_->level_db())) {
    burst_ = profile_->ModulatePacket(*packet);
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
  }
  Put(out.data(), count);
  return true;
}

bool NavaLink::Take(float* out, std::size_t count) {
  while (captured_.size() - captured_at_ < count) {
    // Whole blocks from the device: a system call per tick would cost more than the modem.
    captured_.erase(captured_.begin(), captured_.begin() + static_cast<std::ptrdiff_t>(captured_at_));
    captured_at_ = 0;
    const std::size_t have = captured_.size();
    captured_.resize(have + block_);
    if (!device_.Read(captured_.data() + have, block_)) {
      captured_.resize(have);
      return false;
    }
  }
  std::copy(captured_.begin() + captured_at_, captured_.begin() + captured_at_ + count, out);
  captured_at_ += count;
  return true;
}

void NavaLink::Put(const float* in, std::size_t count) {
  playing_.insert(playing_.end(), in, in + count);
  if (playing_.size() < block_) return;
  device_.Write(playing_.data(), playing_.size());
  playing_.clear();
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

}  // namespace nava_modem
