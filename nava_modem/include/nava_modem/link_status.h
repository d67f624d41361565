#pragma once

#include <cstdint>
#include <string>

#include "nava_modem/csma_mac.h"
#include "nava_modem/packet_receiver.h"

namespace nava_modem {

// What a link has heard, by kind.
struct ReceptionCounts {
  std::uint64_t packets = 0, repaired = 0, zero_byte = 0, one_byte = 0, bad_crc = 0;
  void Add(const RxEvent& e);
};

// A link's state and counts at one moment, for a node to publish and log without holding on
// to the link (NavaLink::status()).
struct LinkStatus {
  MacState state = MacState::kCalibrating;
  double threshold_db = 0.0, level_db = 0.0;
  std::uint64_t sent = 0, queue_drops = 0;
  ReceptionCounts heard;
  // Capture overruns, playback underruns, packets an underrun cut, and catch-ups on a capture
  // backlog (NavaLink).
  std::uint64_t overruns = 0, underruns = 0, packets_cut = 0, catch_ups = 0;
  // The device: down now, why it last failed (or a try to reopen it did), failures, reopens,
  // packets put back to be sent again, tries to reopen that failed since the last failure.
  bool device_down = false;
  std::string device_error;
  std::uint64_t device_faults = 0, reopens = 0, requeued = 0;
  int failed_reopens = 0;
};

}  // namespace nava_modem
