#pragma once

// What the `room` profile receiver reports of the chirps it found: the packet between two chirps
// (or BAD_CRC noise), a long frame's header between its first two chirps and its payload between
// the last two (room_frame.h), and a lone chirp's ONE_BYTE noise. No ROS.
#include <cstddef>
#include <optional>
#include <vector>

#include "nava_modem/chirp_detector.h"
#include "nava_modem/crc16.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_frame.h"
#include "nava_modem/room_symbol_reader.h"
#include "nava_modem/sample_ring.h"

namespace nava_modem {

// A long frame's header, read between its chirps A and B.
struct RoomHeaderFound {
  room_frame::Header header;
  double stretch = 1.0;  // the sender's durations over ours, from A to B
  int corrected = 0;     // coded bits the Viterbi decoder corrected in it
};

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

  // The header of the long frame whose chirp A was found at `a` and whose chirp B starts at
  // `aligned_b`, read as a packet is; nothing when the chirps lie beyond any clock looked for,
  // its CRC-3 fails or it names a rate the ladder lacks.
  std::optional<RoomHeaderFound> DecodeHeader(RoomSymbolReader& symbols, const SampleRing& heard, const ChirpPeak& a,
                                              double aligned_b) const;

  // The long frame whose chirps A and B were found at `a` and `b` with header `found`, and whose
  // chirp C (`c`, found there) starts at `aligned_c`: the payload read between B and C at the
  // clock their distance gives. A packet (data and rate) when the CRC-32 passes, else BAD_CRC
  // noise. The event spans A to the end of C.
  RxEvent DecodePayload(RoomSymbolReader& symbols, const SampleRing& heard, const ChirpPeak& a, const ChirpPeak& b,
                        const RoomHeaderFound& found, const ChirpPeak& c, double aligned_c) const;

  // ONE_BYTE noise for a chirp that began no packet: a packet begun and never ended, or a sound
  // that looked like a chirp.
  RxEvent LoneChirp(const ChirpPeak& chirp) const;

  // Samples from a packet's first chirp to its second, at our clock.
  double packet_length() const { return packet_length_; }
  // Samples from a long frame's chirp A to B, and from B to C for a payload, at our clock.
  double header_length() const { return header_length_; }
  double PayloadLength(const room_frame::Header& header) const;

 private:
  // The soft bits of the `count` symbols (each sounding `tones` sub-bands) after the chirp at
  // `pre` whose partner starts at `aligned_post`, `nominal` samples after it at our clock;
  // nothing when their distance is beyond any clock looked for. `stretch` gets the sender's
  // durations over ours.
  std::optional<std::vector<float>> ReadBlock(RoomSymbolReader& symbols, const SampleRing& heard, double pre,
                                              double aligned_post, double nominal, int count, int tones,
                                              double& stretch) const;
  // An event from `first` to the end of the chirp at `last`, with its mean level (dB FS).
  RxEvent Spanning(const SampleRing& heard, double first, double last) const;

  double sample_rate_;
  std::size_t chirp_length_;
  double max_stretch_error_;
  CrcVariant crc_;
  double packet_length_;
  double header_length_;
};

}  // namespace nava_modem
