#pragma once

// When a nava packet the receiver decoded first reached the microphone (RxEvent::arrival, the
// input of ranging): its known start (PacketTimingReference: the end of the SPACE lead, the
// break, the header byte) timed by an ArrivalTimer in the input kept since, around where the
// decoder placed the packet. The FSK receiver's last stage. No ROS.
#include <cstdint>
#include <memory>
#include <vector>

#include "nava_modem/first_arrival.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/timing_reference.h"

namespace nava_modem {

class NavaPacketTimer {
 public:
  // Keeps enough input that a packet decoded at its end, sent with its clock as far as
  // `max_rate_error` off, can still be timed. `modem` must be valid (ValidateModemOptions).
  NavaPacketTimer(const ModemOptions& modem, double max_rate_error);
  void Push(float sample) { raw_[static_cast<std::size_t>(samples_++) & mask_] = sample; }
  // Seconds from the first sample pushed at which the packet the decoder put at `start` (s)
  // first arrived; NaN at a rate too low for the timing band (under 2 x 5400 Hz) or when the
  // input around it is no longer (or not yet) held.
  double Time(double start);

 private:
  double rate_;
  TimingReference reference_;
  std::unique_ptr<ArrivalTimer> timer_;  // none at a rate too low for the timing band
  std::vector<float> raw_;               // the input, a ring
  std::size_t mask_;
  std::int64_t samples_ = 0;  // pushed
};

}  // namespace nava_modem
