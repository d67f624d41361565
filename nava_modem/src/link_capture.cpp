#include "nava_modem/link_capture.h"

#include <algorithm>

namespace nava_modem {
namespace {

// A link behind its capture has caught up once it is within this share of max_capture_lag.
constexpr double kCaughtUpShare = 0.5;

}  // namespace

LinkCapture::LinkCapture(const CaptureOptions& options, AudioDevice& device, Clock& clock)
    : options_(options),
      device_(device),
      clock_(clock),
      channels_(static_cast<std::size_t>(device.capture_channels())),
      card_rate_(CardRateOptions{options.sample_rate}) {
  if (options_.history_seconds > 0.0) history_.emplace(channels_, options_.history_seconds * options_.sample_rate);
}

bool LinkCapture::Take(float* out, std::size_t count, std::int64_t link_samples) {
  while (captured_.size() - captured_at_ < count) {
    captured_.erase(captured_.begin(), captured_.begin() + static_cast<std::ptrdiff_t>(captured_at_));
    captured_at_ = 0;
    frames_.resize(options_.block * channels_);
    if (!device_.Read(frames_.data(), options_.block)) return false;
    // The receiver hears the first microphone: summing a small array's channels, each a little
    // delayed, would comb-filter the band; the others are kept for the direction.
    for (std::size_t f = 0; f < options_.block; ++f) captured_.push_back(frames_[f * channels_]);
    if (history_) history_->Record(frames_.data(), options_.block);
    card_frames_ += static_cast<std::int64_t>(options_.block);
    const std::size_t waiting = device_.CaptureLag();  // one query of the device a block
    card_rate_.Add(clock_.Now(), card_frames_ + static_cast<std::int64_t>(waiting));
    const double lag = static_cast<double>(waiting) / options_.sample_rate;
    if (!behind_ && lag > options_.max_capture_lag) {
      behind_ = true;
      behind_since_ = link_samples;
      ++catch_ups_;
    } else if (behind_ && lag <= kCaughtUpShare * options_.max_capture_lag) {
      behind_ = false;
    }
  }
  std::copy(captured_.begin() + captured_at_, captured_.begin() + captured_at_ + count, out);
  captured_at_ += count;
  return true;
}

void LinkCapture::Reset() {
  captured_.clear();
  captured_at_ = 0;
  card_rate_.Reset();
  card_frames_ = 0;
  behind_ = false;
}

}  // namespace nava_modem
