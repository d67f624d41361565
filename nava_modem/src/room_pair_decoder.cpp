#include "nava_modem/room_pair_decoder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "nava_modem/frame.h"
#include "nava_modem/room_code.h"
#include "nava_modem/room_phy.h"
#include "nava_modem/room_soft_bits.h"

namespace nava_modem {

using namespace room_phy;

RoomPairDecoder::RoomPairDecoder(double sample_rate, std::size_t chirp_length, double max_stretch_error, CrcVariant crc)
    : sample_rate_(sample_rate),
      chirp_length_(chirp_length),
      max_stretch_error_(max_stretch_error),
      crc_(crc),
      packet_length_(kPostChirpStart * sample_rate) {}

RxEvent RoomPairDecoder::Decode(RoomSymbolReader& symbols, const SampleRing& heard, const ChirpPeak& pre, const ChirpPeak& post,
                                double aligned_post) const {
  const double fs = sample_rate_;
  // The sender's durations over ours: symbol windows are this much longer, tones this much lower.
  const double stretch = (aligned_post - pre.sample) / packet_length_;
  if (std::abs(stretch - 1.0) > max_stretch_error_) {
    // Lined up beyond any clock we look for: not a packet's two chirps.
    RxEvent ev;
    ev.noise = RxEvent::Noise::kBadCrc;
    ev.start = pre.sample / fs;
    ev.end = (post.sample + chirp_length_) / fs;
    ev.level_db = 10.0 * std::log10(pre.power + 1e-20);
    return ev;
  }
  std::vector<double> energy(static_cast<std::size_t>(kSymbols) * kBins);
  symbols.Read(heard, pre.sample, stretch, energy, 1);
  const room_code::Decoded decoded = room_code::Decode(RoomSoftBits(energy));

  RxEvent ev;
  ev.start = pre.sample / fs;
  ev.end = (post.sample + chirp_length_) / fs;
  double power = 0.0;
  const std::int64_t first = std::llround(pre.sample), last = std::llround(post.sample) + static_cast<std::int64_t>(chirp_length_);
  for (std::int64_t n = first; n < last; ++n) power += 2.0 * heard[n] * heard[n];
  ev.level_db = 10.0 * std::log10(power / std::max<std::int64_t>(1, last - first) + 1e-20);
  ev.quality = 1.0 - static_cast<double>(decoded.corrected) / kCodedBits;
  ev.fixed_bits = decoded.corrected;
  ev.rate_error = 1.0 / stretch - 1.0;
  ev.clarity = std::min(pre.ratio, post.ratio);
  Frame frame{};
  frame[0] = kHeader;
  std::copy(decoded.payload.begin(), decoded.payload.end(), frame.begin() + 1);
  if (CrcMatches(frame, crc_)) {
    ev.kind = RxEvent::Kind::kPacket;
    ev.data.assign(frame.begin() + 1, frame.begin() + 1 + kDataBytes);
  } else {
    ev.kind = RxEvent::Kind::kNoise;
    ev.noise = RxEvent::Noise::kBadCrc;
  }
  return ev;
}

RxEvent RoomPairDecoder::LoneChirp(const ChirpPeak& chirp) const {
  RxEvent ev;
  ev.kind = RxEvent::Kind::kNoise;
  ev.noise = RxEvent::Noise::kOneByte;
  ev.start = chirp.sample / sample_rate_;
  ev.end = (chirp.sample + chirp_length_) / sample_rate_;
  ev.level_db = 10.0 * std::log10(chirp.power + 1e-20);
  ev.clarity = chirp.ratio;
  return ev;
}

}  // namespace nava_modem
