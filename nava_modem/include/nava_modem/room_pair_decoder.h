#pragma once

// What the `room` profile receiver reports of the chirps it found: the packet between two chirps
// (or BAD_CRC noise), and a lone chirp's ONE_BYTE noise. No ROS.
#include <cstddef>

#include "nava_modem/chirp_detector.h"
#include "nava_modem/crc16.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_symbol_reader.h"
#include "nava_modem/sample_ring.h"

namespace nava_modem {

class RoomPairDecoder {
 public:
  // `max_stretch_error`: the largest clock error a decode accepts (the sender's durations over
  // ours, less 1); `chirp_length`: samples.
  RoomPairDecoder(double sample_rate, std::size_t chirp_length, double max_stretch_error, CrcVariant crc);

  // The packet whose first chirp was found at `pre` and whose second starts at `aligned_post`
  // (samples, where the alignment put it; `post` is the chirp found there, for the report's end
  // and clarity), read from `heard`: the sender's clock from the chirps' distance, the symbols'
  // tone energies on it (RoomSymbolReader), soft bits (RoomSoftBits), the Viterbi decoder and
  // the CRC. A packet when the CRC passes (its arrival left NaN: timing it is the caller's),
  // else BAD_CRC noise; BAD_CRC too, without a decode, for chirps lined up beyond any clock
  // looked for. The event's level is the mean power from the first chirp to the second's end.
  RxEvent Decode(RoomSymbolReader& symbols, const SampleRing& heard, const ChirpPeak& pre, const ChirpPeak& post,
                 double aligned_post) const;

  // ONE_BYTE noise for a chirp that began no packet: a packet begun and never ended, or a sound
  // that looked like a chirp.
  RxEvent LoneChirp(const ChirpPeak& chirp) const;

  // Samples from a packet's first chirp to its second, at our clock.
  double packet_length() const { return packet_length_; }

 private:
  double sample_rate_;
  std::size_t chirp_length_;
  double max_stretch_error_;
  CrcVariant crc_;
  double packet_length_;
};

}  // namespace nava_modem
