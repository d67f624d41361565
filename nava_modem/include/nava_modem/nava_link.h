#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "nava_modem/audio_device.h"
#include "nava_modem/clock.h"
#include "nava_modem/csma_mac.h"
#include "nava_modem/link_capture.h"
#include "nava_modem/link_playback.h"
#include "nava_modem/link_status.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/receive_chain.h"
#include "nava_modem/reopen_schedule.h"

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
  // The rate step frames go at unless Send() names one (0: the profile's slowest, today's
  // packet for 4 bytes); below the profile's FrameFormat::rates.
  int rate = 0;
  std::uint32_t seed = 1;
};

// Throws std::invalid_argument naming the field, its value and what was expected, for what
// can be judged without the device: the receiver (ValidateReceiverOptions), the reopen
// schedule (ValidateReopenOptions), max_capture_lag and max_loop above 0 and at most 10 s, a rate
// on the profile's ladder. The profile
// checks the modem, and the MAC its options once given the profile's timing.
void ValidateLinkOptions(const LinkOptions& options);

// A whole Nava link on an audio device (thesis section 5.2.4), with any modem profile, wired from
// its capture (LinkCapture), its receive chain (ReceiveChain) and its playback (LinkPlayback)
// round the CSMA-CA MAC: every
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

  // Queues a frame's data bytes (as many as the profile carries: ModemProfile::CheckFrame's
  // error otherwise) to send at `rate` (options' rate unless given); it holds the MAC for its own
  // airtime. False (counted by the MAC) when the queue is full.
  bool Send(std::vector<std::uint8_t> data);
  bool Send(std::vector<std::uint8_t> data, int rate);

  // One tick of audio in and out; what was heard is appended to `events`. False at the end of
  // the device's input. While the device is down, a tick tries to reopen it when that is due
  // and otherwise waits (at most 50 ms, so that the caller can stop) for the next try.
  bool Tick(std::vector<RxEvent>& events);

  const CsmaMac& mac() const { return mac_; }
  double level_db() const { return receive_.level_db(); }
  const ModemProfile& profile() const { return *profile_; }
  bool carrier() const { return mac_.carrier(); }
  // s of audio run (the receiver's clock: audio heard, and the silence a failure ended it with).
  double time() const { return static_cast<double>(samples_done_ + samples_flushed_) / options_.modem.sample_rate; }
  std::uint64_t packets_sent() const { return mac_.sent(); }
  std::uint64_t overruns() const { return device_.overruns(); }
  std::uint64_t underruns() const { return device_.underruns(); }
  // Packets during whose sending the device reported a playback underrun: they went out with
  // a gap, so listeners most likely heard noise.
  std::uint64_t packets_cut() const { return playback_.packets_cut(); }
  // Times the capture fell more than max_capture_lag behind and the link caught up.
  std::uint64_t catch_ups() const { return capture_.catch_ups(); }
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
  // last call; at most ReceiveChain::kMaxOwnTimings wait, and the oldest beyond are dropped and counted.
  std::vector<OwnTiming> TakeOwnTimings() { return receive_.TakeOwnTimings(); }
  std::uint64_t own_timings_dropped() const { return receive_.own_timings_dropped(); }
  // Receptions so far, by kind.
  const ReceptionCounts& heard() const { return heard_; }
  // All of the above at once.
  LinkStatus status() const;
  // The sound card's capture rate over its nominal one, minus 1, against the host's steady
  // clock (card_rate.h); NaN until some 30 s after the device (re)opened.
  double card_rate_error() const { return capture_.card_rate_error(); }

 private:
  bool Run(std::vector<RxEvent>& events);  // a tick on a working device
  void Fail(const std::string& error, std::vector<RxEvent>& events);
  void TryReopen();

  LinkOptions options_;
  AudioDevice& device_;
  Clock& clock_;
  std::unique_ptr<ModemProfile> profile_;
  CsmaMac mac_;
  ReceiveChain receive_;
  LinkCapture capture_;
  LinkPlayback playback_;
  double samples_per_tick_;
  std::uint64_t ticks_ = 0;
  std::int64_t samples_done_ = 0;
  std::int64_t samples_flushed_ = 0;  // heard by the receiver on failures, not in ticks
  std::vector<float> in_;
  ReopenSchedule reopen_;
  bool device_down_ = false;
  std::string device_error_;
  std::uint64_t device_faults_ = 0, reopens_ = 0;
  ReceptionCounts heard_;
};

}  // namespace nava_modem
