#include "nava_modem/room_modulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nava_modem/frame.h"
#include "nava_modem/room_code.h"
#include "nava_modem/room_frame.h"
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

std::vector<float> RoomModulator::Modulate(const std::vector<std::uint8_t>& data, int rate) const {
  const int bytes = static_cast<int>(data.size());
  if (bytes < room_frame::kMinBytes || bytes > room_frame::kMaxBytes) {
    throw std::invalid_argument("room frame: " + std::to_string(bytes) + " data bytes, expected " +
                                std::to_string(room_frame::kMinBytes) + " to " + std::to_string(room_frame::kMaxBytes));
  }
  if (rate < 0 || rate >= room_frame::kRates) {
    throw std::invalid_argument("room frame: rate " + std::to_string(rate) + ", expected 0 to " +
                                std::to_string(room_frame::kRates - 1));
  }
  const double fs = options_.sample_rate;
  auto at = [fs](double seconds) { return static_cast<std::size_t>(std::lround(seconds * fs)); };
  const double seconds = room_frame::FrameSeconds(bytes, rate);
  // Long enough for the last chirp however its start and length round at this rate.
  std::vector<float> out(std::max(at(seconds), at(seconds - room_phy::kChirpSeconds) + chirp_.size()), 0.0f);
  if (room_frame::IsPacket(bytes, rate)) {
    const Frame frame = MakeFrame(data, options_.crc);
    // The header byte is implied: the block is the 4 data bytes and the CRC.
    const std::vector<std::uint8_t> payload(frame.begin() + 1, frame.end());
    PutChirp(out, 0.0);
    PutSymbols(out, room_phy::kDataStart, room_code::EncodeBlock(payload, room_phy::kPayloadBits, room_phy::kSymbols));
    PutChirp(out, room_phy::kPostChirpStart);
    return out;
  }
  const room_frame::Header header{rate, bytes};
  const double b = room_frame::HeaderPairSeconds();
  const double c = b + room_frame::PayloadPairSeconds(bytes, rate);
  PutChirp(out, 0.0);
  PutSymbols(out, room_phy::kChirpSeconds,
             room_code::EncodeBlock(room_frame::HeaderBytes(header), room_frame::kHeaderBits, room_frame::kHeaderSymbols));
  PutChirp(out, b);
  PutSymbols(out, b + room_phy::kChirpSeconds,
             room_code::EncodeBlock(room_frame::PayloadBytes(header, data), room_frame::PayloadBits(bytes),
                                    room_frame::PayloadSymbols(bytes, rate), room_frame::PayloadShape(rate)),
             room_frame::PayloadShape(rate).tones);
  PutChirp(out, c);
  return out;
}

void RoomModulator::PutChirp(std::vector<float>& out, double start) const {
  const std::size_t first = static_cast<std::size_t>(std::lround(start * options_.sample_rate));
  const float a = static_cast<float>(options_.amplitude);
  for (std::size_t k = 0; k < chirp_.size(); ++k) out[first + k] = a * chirp_[k];
}

void RoomModulator::PutSymbols(std::vector<float>& out, double start, const std::vector<int>& tones, int per_symbol) const {
  const double fs = options_.sample_rate;
  auto at = [fs](double seconds) { return static_cast<std::size_t>(std::lround(seconds * fs)); };
  const int symbols = static_cast<int>(tones.size()) / per_symbol;
  // Several tones at once: each at amplitude / sqrt(tones), so the symbol's power is one tone's.
  // (In float, as one tone always was: today's packet stays the same to the sample.)
  const float a = static_cast<float>(options_.amplitude / std::sqrt(static_cast<double>(per_symbol)));
  for (int s = 0; s < symbols; ++s) {
    const double symbol_start = start + s * room_phy::kSymbolSeconds;
    const std::size_t first = at(symbol_start), last = at(symbol_start + room_phy::kSymbolSeconds);
    for (int slot = 0; slot < per_symbol; ++slot) {
      // A whole number of cycles per symbol: every symbol starts and ends at zero, so the hops
      // make no click.
      const int tone = tones[static_cast<std::size_t>(s * per_symbol + slot)];
      const int bin = room_phy::kLowestBin + room_phy::BandOf(s, slot, per_symbol) * room_phy::kTonesPerBand + tone;
      const double w = 2.0 * M_PI * bin * room_phy::kToneSpacingHz / fs;
      for (std::size_t n = first; n < last; ++n) out[n] += a * static_cast<float>(std::sin(w * (n - first)));
    }
  }
}

}  // namespace nava_modem
