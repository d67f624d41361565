#include "nava_modem/link_status.h"

namespace nava_modem {

void ReceptionCounts::Add(const RxEvent& e) {
  const bool packet = e.kind == RxEvent::Kind::kPacket;
  packets += packet;
  repaired += packet && e.fixed_bits > 0;
  zero_byte += e.noise == RxEvent::Noise::kZeroByte;
  one_byte += e.noise == RxEvent::Noise::kOneByte;
  bad_crc += e.noise == RxEvent::Noise::kBadCrc;
}

}  // namespace nava_modem
