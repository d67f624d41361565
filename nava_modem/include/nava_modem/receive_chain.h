#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "nava_modem/capture_history.h"
#include "nava_modem/direction_estimator.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/self_timer.h"

namespace nava_modem {

struct ReceiveChainOptions {
  ReceiverOptions receiver;
  // One per capture channel; two or more give each reception its direction.
  std::vector<Microphone2D> microphones;
  // s the link's own sound may take from playback to its microphone (SelfTimer).
  double max_loop = 0.5;
};

// A link's receive side: the profile's receiver, the timing of the link's own packets as its
// microphone hears them (SelfTimer, for two-way ranging), and each reception's direction from
// its own sound on every microphone (DirectionEstimator over the capture's history).
class ReceiveChain {
 public:
  // Throws std::invalid_argument on impossible receiver options.
  ReceiveChain(const ModemProfile& profile, const ReceiveChainOptions& options);

  // s of every capture channel the directions need kept (CaptureOptions::history_seconds): a
  // packet and what it takes the receiver to report it; 0 without an array.
  double history_seconds() const;

  // Samples heard (of the first channel), `muted` while the link sends or its echo lasts;
  // receptions are appended to `events`, with directions from `history` when there is an array.
  void Hear(const float* samples, std::size_t count, bool muted, std::vector<RxEvent>& events, const CaptureHistory* history);
  // The link sent a packet at `time` (s on the receiver's clock): its own sound is looked for.
  void Sent(const std::vector<std::uint8_t>& data, double time);
  // The thesis's receiver threshold is the MAC's, known once its calibration ends: from then
  // on busy air with no packet is ZERO_BYTE noise. Only the first call counts.
  void ShareCarrierThreshold(double db);
  // The device failed: the samples it had captured and were not heard are decoded as if silence
  // followed (a packet that had just ended is reported now, one cut short ends as noise or
  // nothing, and the audio after the reopen begins nothing half-heard), and the history
  // records that silence. Returns the samples of silence the receiver's clock moved past.
  std::int64_t EndHearing(const float* unheard, std::size_t count, std::vector<RxEvent>& events, CaptureHistory* history);

  double level_db() const { return receiver_->level_db(); }
  double time() const { return receiver_->time(); }
  // The link's own packets as its microphone heard them, since the last call; at most
  // kMaxOwnTimings wait, and the oldest beyond are dropped and counted.
  std::vector<OwnTiming> TakeOwnTimings();
  std::uint64_t own_timings_dropped() const { return own_timings_dropped_; }
  static constexpr std::size_t kMaxOwnTimings = 64;

 private:
  void KeepOwnTimings(std::vector<OwnTiming>& fresh);
  void EstimateDirections(std::vector<RxEvent>& events, std::size_t first, const CaptureHistory* history);

  const ModemProfile& profile_;
  ReceiveChainOptions options_;
  double sample_rate_;
  std::unique_ptr<PacketReceiver> receiver_;
  bool threshold_shared_ = false;
  SelfTimer self_timer_;
  std::vector<OwnTiming> own_timings_;
  std::uint64_t own_timings_dropped_ = 0;
  std::unique_ptr<DirectionEstimator> estimator_;
  std::vector<std::vector<float>> span_;  // scratch: an event's samples per channel
};

}  // namespace nava_modem
