#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "nava_modem/audio_device.h"
#include "nava_modem/card_rate.h"
#include "nava_modem/clock.h"
#include "nava_modem/csma_mac.h"
#include "nava_modem/direction_estimator.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/reopen_schedule.h"
#include "nava_modem/self_timer.h"

namespace nava_modem {

struct LinkOptions {
  Profile profile = Profile::kNava;
  // Where the capture channels' microphones sit (m, robot frame), one per channel. Two or more
  // give each reception its direction; none (or one) leaves it NaN.
  std::vector<Microphone2D> microphones;
  ModemOptions modem;
  MacOptions mac;  // its bit rate and packet length are the profile's (MacTiming)
  ReceiverOptions receiver;
  ReopenOptions reopen;  // after a device failure
  // s the capture may fall behind real time (a stalled process, on a sound server that keeps
  // what was not read) before the link catches up: it then skips playing silence and starts no
  // send (for up to 2 s) until it is within half of this again. Audio heard late makes carrier
  // sense stale and lets the link's own echo outlast its deaf time.
  double max_capture_lag = 0.1;
  // s its own sound may take from playback to its microphone (the device's and the sound
  // server's buffers): each packet it sends is looked for that long in what it captures, and
  // timed (OwnTiming), for two-way ranging (unless receiver.time_arrivals is off).
  double max_loop = 0.5;
  std::uint32_t seed = 1;
};

// Throws std::invalid_argument naming the field, its value and what was expected, for what
// can be judged without the device: the receiver (ValidateReceiverOptions), the reopen
// schedule (ValidateReopenOptions), max_capture_lag and max_loop above 0 and at most 10 s. The profile
// checks the modem, and the MAC its options once given the profile's timing.
void ValidateLinkOptions(const LinkOptions& options);

// A whole Nava link on an audio device (thesis section 5.2.4), with any modem profile: every
// tick (1/16 of the profile's MAC bit) it reads
// a tick of audio, runs the receiver on it (deaf while sending and for the echo time after),
// tells the CSMA-CA MAC the level heard, and writes a tick of the packet being sent, or of
// silence. Single-threaded: the caller runs Tick() in a loop.
//
// When the device fails (DeviceFault), the link counts it, decodes what it had heard as if
// silence followed, and puts every packet whose sound had not all played (by the device's
// playback position) back at the front of the MAC's queue, so that across the failure none is
// lost and none sent twice; it then reopens the device on `options.reopen`'s schedule, waiting
// on `clock`, and listens for its settle time before sending again.
class NavaLink {
 public:
  // Throws std::invalid_argument on impossible options.
  NavaLink(const LinkOptions& options, AudioDevice& device, Clock& clock = SteadyClock::Instance());

  // Queues 4 data bytes to send; false (counted by the MAC) when the queue is full.
  bool Send(std::vector<std::uint8_t> data);

  // One tick of audio in and out; what was heard is appended to `events`. False at the end of
  // the device's input. While the device is down, a tick tries to reopen it when that is due
  // and otherwise waits (at most 50 ms, so that the caller can stop) for the next try.
  bool Tick(std::vector<RxEvent>& events);

  const CsmaMac& mac() const { return mac_; }
  double level_db() const { return receiver_->level_db(); }
  const ModemProfile& profile() const { return *profile_; }
  bool carrier() const { return mac_.carrier(); }
  // s of audio run (the receiver's clock: audio heard, and the silence a failure ended it with).
  double time() const { return static_cast<double>(samples_done_ + samples_flushed_) / options_.modem.sample_rate; }
  std::uint64_t packets_sent() const { return mac_.sent(); }
  std::uint64_t overruns() const { return device_.overruns(); }
  std::uint64_t underruns() const { return device_.underruns(); }
  // Packets during whose sending the device reported a playback underrun: they went out with
  // a gap, so listeners most likely heard noise.
  std::uint64_t packets_cut() const { return packets_cut_; }
  // Times the capture fell more than max_capture_lag behind and the link caught up.
  std::uint64_t catch_ups() const { return catch_ups_; }
  // Device failures: whether it is down now, why it last failed (or a try to reopen it did),
  // failures so far, reopens that worked, tries that failed since the last failure, and
  // packets put back to be sent again because their sound had not all played.
  bool device_down() const { return device_down_; }
  const std::string& device_error() const { return device_error_; }
  std::uint64_t device_faults() const { return device_faults_; }
  std::uint64_t reopens() const { return reopens_; }
  int failed_reopens() const { return reopen_.failed_tries(); }
  std::uint64_t packets_requeued() const { return mac_.requeued(); }
  // Its own packets as its microphone heard them (SelfTimer), on the receiver's clock, since the
  // last call; at most kMaxOwnTimings wait, and the oldest beyond are dropped and counted.
  std::vector<OwnTiming> TakeOwnTimings();
  std::uint64_t own_timings_dropped() const { return own_timings_dropped_; }
  static constexpr std::size_t kMaxOwnTimings = 64;
  // The sound card's capture rate over its nominal one, minus 1, against the host's steady
  // clock (card_rate.h); NaN until some 30 s after the device (re)opened.
  double card_rate_error() const { return card_rate_.rate_error(); }

 private:
  LinkOptions options_;
  AudioDevice& device_;
  std::unique_ptr<ModemProfile> profile_;
  std::unique_ptr<PacketReceiver> receiver_;
  CsmaMac mac_;
  double samples_per_tick_;
  std::uint64_t ticks_ = 0;
  std::int64_t samples_done_ = 0;
  std::int64_t samples_flushed_ = 0;  // heard by the receiver on failures, not in ticks
  bool Run(std::vector<RxEvent>& events);  // a tick on a working device
  void Fail(const std::string& error, std::vector<RxEvent>& events);
  void EndHearing(std::vector<RxEvent>& events);
  void TryReopen();
  bool Take(float* out, std::size_t count);  // captured samples, read from the device by blocks
  // Each event's direction from its own samples on every microphone.
  void EstimateDirections(std::vector<RxEvent>& events, std::size_t first);
  void Put(const float* in, std::size_t count);  // samples to play, written by blocks
  void Write();                                  // what waits in playing_

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
  bool behind_ = false;  // catching up on a capture backlog
  std::int64_t behind_since_ = 0;  // samples_done_ when it fell behind
  std::uint64_t catch_ups_ = 0;
  bool burst_cut_ = false;  // the packet being sent has been counted in packets_cut_
  std::size_t burst_written_ = 0, burst_pending_ = 0;  // its samples written, and waiting in playing_

  // Playback since the device was last (re)opened, in samples: handed to Put(), written to
  // the device, and known to have played. A packet leaves `in_flight_` once its end has played.
  struct InFlight {
    CsmaMac::Packet data;
    std::int64_t end;
  };
  std::deque<InFlight> in_flight_;
  std::int64_t queued_out_ = 0, written_ = 0, played_ = 0;

  SelfTimer self_timer_;
  std::vector<OwnTiming> own_timings_;
  std::uint64_t own_timings_dropped_ = 0;
  void KeepOwnTimings(std::vector<OwnTiming>& fresh);

  Clock& clock_;
  CardRateTracker card_rate_;
  std::int64_t card_frames_ = 0;  // frames read since the device (re)opened
  ReopenSchedule reopen_;
  bool device_down_ = false;
  std::string device_error_;
  std::uint64_t device_faults_ = 0, reopens_ = 0;
};

}  // namespace nava_modem
