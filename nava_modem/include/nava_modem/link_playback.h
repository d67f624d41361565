#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "nava_modem/audio_device.h"
#include "nava_modem/csma_mac.h"

namespace nava_modem {

// A link's playback side: plays each tick's share of the packet being sent, or silence, writes
// the device in blocks, follows what has played (the device's write position less its
// playback delay) so that a failure knows which packets did not all reach the air, and counts
// the packets an underrun cut.
class LinkPlayback {
 public:
  // Writes of at least `block` samples.
  LinkPlayback(AudioDevice& device, std::size_t block);

  // A packet's sound, to start with the next tick.
  void Start(MacFrame packet, std::vector<float> sound);
  // Plays a tick of `count` samples: what is left of the packet, else silence. A link `behind`
  // its capture plays silence only where it needs no wait (the device kept what it captured
  // while the process stalled, so the link runs faster than real time until it has heard that
  // backlog; no captured sound is lost). Throws DeviceFault from the device.
  void Tick(std::size_t count, bool behind);
  // Packets during whose sending the device reported a playback underrun.
  std::uint64_t packets_cut() const { return packets_cut_; }
  // The device failed: the packets whose end had not played (as of the last write), in the
  // order sent, and playback starts anew.
  std::vector<MacFrame> Abort();
  // The device reopened: underruns counted until now are not this playback's.
  void Reopened() { underruns_seen_ = device_.underruns(); }

 private:
  void Put(const float* samples, std::size_t count);
  void Write();  // what waits in playing_

  AudioDevice& device_;
  std::size_t block_;
  std::vector<float> burst_;  // the packet being sent
  std::size_t burst_at_ = 0;
  bool burst_cut_ = false;  // it has been counted in packets_cut_
  std::size_t burst_written_ = 0, burst_pending_ = 0;  // its samples written, and waiting in playing_
  std::vector<float> out_, playing_;
  std::uint64_t underruns_seen_ = 0;
  std::uint64_t packets_cut_ = 0;
  // Since the device was last (re)opened, in samples: handed to Put(), written to the device,
  // and known to have played. A packet leaves `in_flight_` once its end has played.
  struct InFlight {
    MacFrame data;
    std::int64_t end;
  };
  std::deque<InFlight> in_flight_;
  std::int64_t queued_out_ = 0, written_ = 0, played_ = 0;
};

}  // namespace nava_modem
