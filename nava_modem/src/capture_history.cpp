#include "nava_modem/capture_history.h"

#include "nava_modem/power_of_two.h"

namespace nava_modem {

CaptureHistory::CaptureHistory(std::size_t channels, double frames) {
  const std::size_t size = PowerOfTwoAtLeast(frames);
  rings_.assign(channels, std::vector<float>(size, 0.0f));
  mask_ = size - 1;
}

void CaptureHistory::Record(const float* interleaved, std::size_t count) {
  const std::size_t channels = rings_.size();
  for (std::size_t f = 0; f < count; ++f) {
    const std::size_t at = static_cast<std::size_t>(end_ + static_cast<std::int64_t>(f)) & mask_;
    for (std::size_t c = 0; c < channels; ++c) rings_[c][at] = interleaved[f * channels + c];
  }
  end_ += static_cast<std::int64_t>(count);
}

void CaptureHistory::RecordSilence(std::int64_t count) {
  for (std::int64_t n = end_; n < end_ + count; ++n) {
    for (std::vector<float>& ring : rings_) ring[static_cast<std::size_t>(n) & mask_] = 0.0f;
  }
  end_ += count;
}

void CaptureHistory::Copy(std::int64_t from, std::int64_t to, std::vector<std::vector<float>>& out) const {
  out.resize(rings_.size());
  for (std::size_t c = 0; c < rings_.size(); ++c) {
    out[c].resize(static_cast<std::size_t>(to - from));
    for (std::int64_t n = from; n < to; ++n) out[c][static_cast<std::size_t>(n - from)] = rings_[c][static_cast<std::size_t>(n) & mask_];
  }
}

}  // namespace nava_modem
