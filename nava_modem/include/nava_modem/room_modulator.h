#pragma once

#include <cstdint>
#include <vector>

#include "nava_modem/modem_options.h"

namespace nava_modem {

// The `room` profile's transmitter: today's packet (room_phy.h: chirp, 42 hopping 16-ary FSK
// symbols carrying the convolutionally coded payload, chirp) and long frames of any length
// (room_frame.h). Uses the options' sample rate, amplitude and CRC; the FSK tones and bit rate
// belong to the nava profile and are ignored.
class RoomModulator {
 public:
  explicit RoomModulator(const ModemOptions& options);  // throws when the rate cannot carry the band

  // One frame for 1 to 255 data bytes at a rate of the ladder (room_frame::FrameSeconds long):
  // 4 bytes at rate 0 are today's packet. Throws std::invalid_argument naming the length or
  // rate the profile does not carry.
  std::vector<float> Modulate(const std::vector<std::uint8_t>& data, int rate) const;
  // Today's packet for 4 data bytes, kPacketSeconds long.
  std::vector<float> ModulatePacket(const std::vector<std::uint8_t>& data) const { return Modulate(data, 0); }

 private:
  // The chirp at `start` seconds into `out`, and the symbols of one block from `start`, each
  // sounding `per_symbol` of `tones` at once (room_phy::BandOf), at equal shares of the power.
  void PutChirp(std::vector<float>& out, double start) const;
  void PutSymbols(std::vector<float>& out, double start, const std::vector<int>& tones, int per_symbol = 1) const;

  ModemOptions options_;
  std::vector<float> chirp_;
};

// Throws std::invalid_argument naming the rate when the room profile's band (up to 5400 Hz,
// with room for a 5 % clock offset) does not fit below its Nyquist frequency.
void ValidateRoomRate(double sample_rate);

}  // namespace nava_modem
