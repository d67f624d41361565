#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace nava_modem {

// Every capture channel's recent samples, by frame number since the link started (a ring a
// power of two long), so that a reception's direction can be read from its own sound on each
// microphone after the receiver has reported it.
class CaptureHistory {
 public:
  // Keeps at least `frames` frames of `channels` channels.
  CaptureHistory(std::size_t channels, double frames);

  // Appends `count` interleaved frames as read from the device.
  void Record(const float* interleaved, std::size_t count);
  // Appends `count` frames of silence (the time a failed device did not capture).
  void RecordSilence(std::int64_t count);
  // Frames recorded so far; the oldest still held.
  std::int64_t end() const { return end_; }
  std::int64_t oldest() const { return end_ - static_cast<std::int64_t>(mask_); }
  std::size_t channels() const { return rings_.size(); }
  // Frames [from, to) of every channel into `out` (resized), which the caller keeps.
  void Copy(std::int64_t from, std::int64_t to, std::vector<std::vector<float>>& out) const;

 private:
  std::vector<std::vector<float>> rings_;
  std::size_t mask_;
  std::int64_t end_ = 0;
};

}  // namespace nava_modem
