#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace nava_modem {

struct ReceiverOptions {
  // nava profile: how clear the break's SPACE-to-MARK step must be to decode a frame after it:
  // both how much MARK outweighs SPACE over the 10 bits after it and SPACE outweighs MARK over
  // the 10 bits before, each from -1 to 1. Noise alone stays near 0; a clean break gives 1.
  double detect_threshold = 0.4;
  // nava profile: bit-rate mismatch between sender and receiver searched for, as a fraction.
  double max_rate_error = 0.035;
  // nava profile: bits the CRC may repair (0, 1 or 2; see RepairFrame); with 2, one error event
  // of the equaliser's search (3 or 4 bits, RepairEvent) as well.
  int max_fixed_bits = 2;
  // Every profile: in-band level (dB of full scale) above which the air counts as busy, for
  // ZERO_BYTE reports of busy air in which no frame was found. None: such air is not reported.
  std::optional<double> carrier_threshold_db;
  // Every profile: time each packet's first arrival (RxEvent::arrival, for ranging); off, it
  // stays NaN and costs nothing.
  bool time_arrivals = true;
};

// Throws std::invalid_argument naming the field, its value and what was expected:
// detect_threshold from 0.05 to 1 (below, noise alone would pass for a break), max_rate_error
// above 0 and below 0.2, max_fixed_bits 0 to 2, a finite carrier_threshold_db. Every profile's
// receiver is made through ModemProfile::MakeReceiver, which checks them.
void ValidateReceiverOptions(const ReceiverOptions& options);

// The carrier threshold for recordings (nava_decode --threshold-db, and the decode tables
// measured on rendered recordings, which must judge busy air as nava_decode does): busy air at or
// above this in-band level, dB of full scale, in which no frame is found is reported as
// ZERO_BYTE noise.
constexpr double kToolCarrierThresholdDb = -40.0;

// What a receiver heard (thesis section 5.2.4): a packet, or noise of some kind.
struct RxEvent {
  enum class Kind { kPacket, kNoise };
  enum class Noise { kNone, kZeroByte, kOneByte, kBadCrc };
  Kind kind = Kind::kNoise;
  Noise noise = Noise::kNone;
  std::vector<std::uint8_t> data;  // a packet's data bytes (ModemProfile::Format: 4 today)
  int rate = 0;                    // the rate step it came at (FrameFormat::rates)
  double start = 0.0, end = 0.0;   // s since the first sample
  double level_db = 0.0;           // mean in-band level, dB of full scale
  double quality = 0.0;            // how clean the symbols were, 0 to 1 (see each receiver)
  int fixed_bits = 0;              // bits (nava) or coded bits (room) the error correction repaired
  double rate_error = 0.0;         // the sender's clock over ours, minus 1
  double clarity = 0.0;            // how clear the synchronisation was; 0 if none
  // Where it came from (rad, CCW from the receiver's +x; NaN unknown) and how sure that is
  // (0 to 1), from a microphone array; a single microphone leaves them NaN and 0.
  double direction = std::numeric_limits<double>::quiet_NaN();
  double direction_confidence = 0.0;
  // When the packet's first sample, as sent, reached the microphone by the shortest way (the
  // leading edge of its direct or diffracted sound, first_arrival.h), s since the first sample,
  // finer than a sample; NaN where the receiver does not time packets or for noise.
  double arrival = std::numeric_limits<double>::quiet_NaN();
};
const char* NoiseName(RxEvent::Noise noise);  // none, zero_byte, one_byte, bad_crc

// The receiving half of a modem profile: samples in, packets and noise reports out. The link
// above it (NavaLink) does not know which profile it runs.
class PacketReceiver {
 public:
  virtual ~PacketReceiver() = default;
  // Feeds samples; appends what ended within them to `events`.
  virtual void Process(const float* samples, std::size_t count, std::vector<RxEvent>& events) = 0;
  // End of stream: decodes what is pending as if silence followed.
  virtual void Flush(std::vector<RxEvent>& events) = 0;
  // While muted (the link is sending, or deaf to its own echo) nothing is detected.
  virtual void SetMuted(bool muted) = 0;
  virtual void SetCarrierThreshold(std::optional<double> db) = 0;
  // In-band level of the most recent audio (about a bit or a few ms), dB of full scale.
  virtual double level_db() const = 0;
  virtual double time() const = 0;  // s of audio processed
};

}  // namespace nava_modem
