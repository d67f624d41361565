#include "nava_modem/timing_reference.h"

#include "nava_modem/frame.h"
#include "nava_modem/fsk_modulator.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {

TimingReference PacketTimingReference(Profile profile, const ModemOptions& options) {
  TimingReference r;
  if (profile == Profile::kRoom) {
    r.sound = room_phy::Chirp(options.sample_rate);
    return r;
  }
  // Bits before kEndTimedBit carry no data: any payload gives them.
  const std::vector<std::uint8_t> bits = PacketBits(MakeFrame({0, 0, 0, 0}, options.crc));
  r.sound = FskModulator(options).Modulate(std::vector<std::uint8_t>(bits.begin() + kFirstTimedBit, bits.begin() + kEndTimedBit));
  r.offset = kFirstTimedBit * options.sample_rate / options.baud;
  return r;
}

}  // namespace nava_modem
