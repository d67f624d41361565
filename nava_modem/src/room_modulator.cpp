#include "nava_modem/room_modulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nava_modem/frame.h"
#include "nava_modem/room_code.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {

void ValidateRoomRate(double sample_rate) {
  const double needed = 2.0 * room_phy::kHighestHz * 1.05;
  ValidateSampleRate("profile room: sample rate", sample_rate);
  if (!(sample_rate >= needed)) {
    throw std::invalid_argument("profile room: sample rate " + std::to_string(std::lround(sample_rate)) +
                                " Hz cannot carry its band (600 to 5400 Hz): expected " +
                                std::to_string(static_cast<int>(std::ceil(needed))) + " to " +
                                std::to_string(std::lround(kMaxSampleRate)) + " Hz");
  }
}

RoomModulator::RoomModulator(const ModemOptions& options) : options_(options) {
  ValidateRoomRate(options_.sample_rate);
  ValidateAmplitude(options_.amplitude);
  chirp_ = room_phy::Chirp(options_.sample_rate);
}

std::vector<float> RoomModulator::ModulatePacket(const std::vector<std::uint8_t>& data) const {
  const Frame frame = MakeFrame(data, options_.crc);
  room_code::Payload payload{};
  for (int k = 0; k < room_phy::kPayloadBytes; ++k) payload[k] = frame[1 + k];  // the header is implied
  const room_code::Tones tones = room_code::Encode(payload);

  const double fs = options_.sample_rate;
  auto at = [fs](double seconds) { return static_cast<std::size_t>(std::lround(seconds * fs)); };
  // Long enough for the second chirp however its start and length round at this rate.
  std::vector<float> out(std::max(at(room_phy::kPacketSeconds), at(room_phy::kPostChirpStart) + chirp_.size()), 0.0f);
  const float a = static_cast<float>(options_.amplitude);
  for (std::size_t k = 0; k < chirp_.size(); ++k) {
    out[k] = a * chirp_[k];
    out[at(room_phy::kPostChirpStart) + k] = a * chirp_[k];
  }
  for (int s = 0; s < room_phy::kSymbols; ++s) {
    const double start = room_phy::kDataStart + s * room_phy::kSymbolSeconds;
    const std::size_t first = at(start), last = at(start + room_phy::kSymbolSeconds);
    // A whole number of cycles per symbol: every symbol starts and ends at zero, so the
    // hops make no click.
    const double w = 2.0 * M_PI * room_phy::Bin(s, tones[s]) * room_phy::kToneSpacingHz / fs;
    for (std::size_t n = first; n < last; ++n) out[n] = a * static_cast<float>(std::sin(w * (n - first)));
  }
  return out;
}

}  // namespace nava_modem
