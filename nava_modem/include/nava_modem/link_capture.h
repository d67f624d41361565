#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "nava_modem/audio_device.h"
#include "nava_modem/capture_history.h"
#include "nava_modem/card_rate.h"
#include "nava_modem/clock.h"

namespace nava_modem {

struct CaptureOptions {
  double sample_rate = 48000.0;
  // Frames a read from the device asks for.
  std::size_t block = 240;
  // s the capture may fall behind real time before the link counts a catch-up (LinkOptions).
  double max_capture_lag = 0.1;
  // s of every channel to keep for the directions; 0 keeps none.
  double history_seconds = 0.0;
};

// A link's capture side: reads the device in whole blocks (a system call per tick would cost
// more than the modem) and hands out the first channel sample by sample, keeps every channel's
// recent frames for the directions (CaptureHistory), watches how far the capture lags behind
// the device, and tracks the card's rate against the host's clock (CardRateTracker).
class LinkCapture {
 public:
  LinkCapture(const CaptureOptions& options, AudioDevice& device, Clock& clock);

  // The next `count` samples of the first channel into `out`; false at the end of the device's
  // input. `link_samples` is the link's clock (samples run), kept as when a lag began.
  // Throws DeviceFault from the device.
  bool Take(float* out, std::size_t count, std::int64_t link_samples);
  // Behind real time: carrier sense is stale. Since link_samples `behind_since()`.
  bool behind() const { return behind_; }
  std::int64_t behind_since() const { return behind_since_; }
  std::uint64_t catch_ups() const { return catch_ups_; }
  // What was read from the device and not yet taken.
  const float* unheard() const { return captured_.data() + captured_at_; }
  std::size_t unheard_count() const { return captured_.size() - captured_at_; }
  // Every channel's recent frames, when kept.
  CaptureHistory* history() { return history_ ? &*history_ : nullptr; }
  double card_rate_error() const { return card_rate_.rate_error(); }
  // The device failed: what was read and not taken is dropped, the card's frames count from 0
  // again when it reopens, and the lag is forgotten. The history keeps running (the caller
  // records the silence the failure left).
  void Reset();

 private:
  CaptureOptions options_;
  AudioDevice& device_;
  Clock& clock_;
  std::size_t channels_;       // captured per frame; the receiver hears the first
  std::vector<float> frames_;  // a block as read, interleaved
  std::vector<float> captured_;
  std::size_t captured_at_ = 0;
  std::optional<CaptureHistory> history_;
  CardRateTracker card_rate_;
  std::int64_t card_frames_ = 0;  // frames read since the device (re)opened
  bool behind_ = false;
  std::int64_t behind_since_ = 0;
  std::uint64_t catch_ups_ = 0;
};

}  // namespace nava_modem
