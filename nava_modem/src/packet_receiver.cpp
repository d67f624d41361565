#include "nava_modem/packet_receiver.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nava_modem {

void ValidateReceiverOptions(const ReceiverOptions& o) {
  std::ostringstream why;
  if (!(o.detect_threshold >= 0.05 && o.detect_threshold <= 1.0)) {
    why << "receiver detect_threshold " << o.detect_threshold << ": expected 0.05 to 1";
  } else if (!(o.max_rate_error > 0.0 && o.max_rate_error < 0.2)) {
    why << "receiver max_rate_error " << o.max_rate_error << ": expected above 0 and below 0.2";
  } else if (!(o.max_fixed_bits >= 0 && o.max_fixed_bits <= 2)) {
    why << "receiver max_fixed_bits " << o.max_fixed_bits << ": expected 0, 1 or 2";
  } else if (o.carrier_threshold_db && !std::isfinite(*o.carrier_threshold_db)) {
    why << "receiver carrier_threshold_db " << *o.carrier_threshold_db << ": expected a finite level in dB";
  } else {
    return;
  }
  throw std::invalid_argument(why.str());
}

const char* NoiseName(RxEvent::Noise noise) {
  switch (noise) {
    case RxEvent::Noise::kNone: return "none";
    case RxEvent::Noise::kZeroByte: return "zero_byte";
    case RxEvent::Noise::kOneByte: return "one_byte";
    case RxEvent::Noise::kBadCrc: return "bad_crc";
  }
  return "?";
}

}  // namespace nava_modem
