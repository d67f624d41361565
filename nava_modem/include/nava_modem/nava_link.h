#pragma once

#include <cstdint>
#include <vector>

#include "nava_modem/audio_device.h"
#include "nava_modem/csma_mac.h"
#include "nava_modem/direction_estimator.h"
#include "nava_modem/modem_profile.h"

namespace nava_modem {

struct LinkOptions {
  Profile profile = Profile::kNava;
  // Where the capture channels' microphones sit (m, robot frame), one per channel. Two or more
  // give each reception its direction; none (or one) leaves it NaN.
  std::vector<Microphone2D> microphones;
  ModemOptions modem;
  MacOptions mac;  // its bit rate and packet length are the profile's (MacTiming)
  ReceiverOptions receiver;
  std::uint32_t seed = 1;
};

// A whole Nava link on an audio device (thesis section 5.2.4), with any modem profile: every
// tick (1/16 of the profile's MAC bit) it reads
// a tick of audio, runs the receiver on it (deaf while sending and for the echo time after),
// tells the CSMA-CA MAC the level heard, and writes a tick of the packet being sent, or of
// silence. Single-threaded: the caller runs Tick() in a loop.
class NavaLink {
 public:
  NavaLink(const LinkOptions& options, AudioDevice& device);  // throws on impossible options

  // Queues 4 data bytes to send; false (counted by the MAC) when the queue is full.
  bool Send(std::vector<std::uint8_t> data);

  // One tick of audio in and out; what was heard is appended to `events`. False at the end of
  // the device's input.
  bool Tick(std::vector<RxEvent>& events);

  const CsmaMac& mac() const { return mac_; }
  double level_db() const { return receiver_->level_db(); }
  const ModemProfile& profile() const { return *profile_; }
  bool carrier() const { return mac_.carrier(); }
  double time() const { return ticks_ * mac_.tick_seconds(); }  // s of audio run
  std::uint64_t packets_sent() const { return mac_.sent(); }
  std::uint64_t overruns() const { return device_.overruns(); }
  std::uint64_t underruns() const { return device_.underruns(); }
  // Packets during whose sending the device reported a playback underrun: they went out with
  // a gap, so listeners most likely heard noise.
  std::uint64_t packets_cut() const { return packets_cut_; }

 private:
  LinkOptions options_;
  AudioDevice& device_;
  std::unique_ptr<ModemProfile> profile_;
  std::unique_ptr<PacketReceiver> receiver_;
  CsmaMac mac_;
  double samples_per_tick_;
  std::uint64_t ticks_ = 0;
  std::int64_t samples_done_ = 0;
  bool Take(float* out, std::size_t count);  // captured samples, read from the device by blocks
  // Each event's direction from its own samples on every microphone.
  void EstimateDirections(std::vector<RxEvent>& events, std::size_t first);
  void Put(const float* in, std::size_t count);  // samples to play, written by blocks

  std::size_t block_;
  std::size_t channels_;          // captured per frame; the receiver hears the first
  std::vector<float> frames_;     // a block as read, interleaved
  std::vector<float> captured_, playing_;
  // Every channel's recent samples, by frame number (a ring), for the direction estimator.
  std::vector<std::vector<float>> history_;
  std::size_t history_mask_ = 0;
  std::int64_t frames_read_ = 0;
  std::unique_ptr<DirectionEstimator> estimator_;
  std::vector<std::vector<float>> span_;  // scratch: an event's samples per channel
  std::size_t captured_at_ = 0;
  std::vector<float> in_, burst_;
  std::size_t burst_at_ = 0;
  bool threshold_shared_ = false;  // the receiver has the MAC's carrier threshold
  std::uint64_t underruns_seen_ = 0;
  std::uint64_t packets_cut_ = 0;
  bool burst_cut_ = false;  // the packet being sent has been counted in packets_cut_
  std::size_t burst_written_ = 0, burst_pending_ = 0;  // its samples written, and waiting in playing_
};

}  // namespace nava_modem
