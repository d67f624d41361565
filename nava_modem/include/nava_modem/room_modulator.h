#pragma once

#include <cstdint>
#include <vector>

#include "nava_modem/modem_options.h"

namespace nava_modem {

// The `room` profile's transmitter (see room_phy.h): chirp, 42 hopping 16-ary FSK symbols
// carrying the convolutionally coded payload, chirp. Uses the options' sample rate, amplitude
// and CRC; the FSK tones and bit rate belong to the nava profile and are ignored.
class RoomModulator {
 public:
  explicit RoomModulator(const ModemOptions& options);  // throws when the rate cannot carry the band

  // One packet for 4 data bytes, kPacketSeconds long.
  std::vector<float> ModulatePacket(const std::vector<std::uint8_t>& data) const;

 private:
  ModemOptions options_;
  std::vector<float> chirp_;
};

// Throws std::invalid_argument naming the rate when the room profile's band (up to 5400 Hz,
// with room for a 5 % clock offset) does not fit below its Nyquist frequency.
void ValidateRoomRate(double sample_rate);

}  // namespace nava_modem
