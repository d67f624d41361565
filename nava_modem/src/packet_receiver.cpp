#include "nava_modem/packet_receiver.h"

namespace nava_modem {

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
