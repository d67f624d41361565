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

namespace {

// Headers read from speech and from other frames' symbols (chirp pairs at the header's distance
// in the measured rooms' recordings, compare_decodes.sh's files) needed 14 to 33 of the 63 coded
// bits corrected, 23 in the middle; the headers of frames sent through the measured rooms at
// white SNR 10 dB, 0 to 13 but for one in ten. 18 keeps nine in ten of the true and passes one
// in thirty of the false.
constexpr int kMostHeaderCorrections = 18;

}  // namespace

RoomPairDecoder::RoomPairDecoder(double sample_rate, std::size_t chirp_length, double max_stretch_error, CrcVariant crc)
    : sample_rate_(sample_rate),
      chirp_length_(chirp_length),
      max_stretch_error_(max_stretch_error),
      crc_(crc),
      packet_length_(kPostChirpStart * sample_rate),
      header_length_(room_frame::HeaderPairSeconds() * sample_rate) {}

double RoomPairDecoder::PayloadLength(const room_frame::Header& header) const {
  return room_frame::PayloadPairSeconds(header.bytes, header.rate) * sample_rate_;
}

std::optional<std::vector<float>> RoomPairDecoder::ReadBlock(RoomSymbolReader& symbols, const SampleRing& heard, double pre,
                                                             double aligned_post, double nominal, int count, int tones,
                                                             double& stretch) const {
  // The sender's durations over ours: symbol windows are this much longer, tones this much lower.
  stretch = (aligned_post - pre) / nominal;
  if (std::abs(stretch - 1.0) > max_stretch_error_) return std::nullopt;  // beyond any clock looked for
  std::vector<double> energy(static_cast<std::size_t>(count) * kBins);
  symbols.Read(heard, pre, stretch, count, energy, 1);
  return RoomSoftBits(energy, count, tones);
}

RxEvent RoomPairDecoder::Spanning(const SampleRing& heard, double first, double last) const {
  RxEvent ev;
  ev.start = first / sample_rate_;
  ev.end = (last + chirp_length_) / sample_rate_;
  double power = 0.0;
  const std::int64_t from = std::llround(first), to = std::llround(last) + static_cast<std::int64_t>(chirp_length_);
  for (std::int64_t n = from; n < to; ++n) power += 2.0 * heard[n] * heard[n];
  ev.level_db = 10.0 * std::log10(power / std::max<std::int64_t>(1, to - from) + 1e-20);
  return ev;
}

RxEvent RoomPairDecoder::Decode(RoomSymbolReader& symbols, const SampleRing& heard, const ChirpPeak& pre, const ChirpPeak& post,
                                double aligned_post) const {
  double stretch = 1.0;
  const std::optional<std::vector<float>> soft = ReadBlock(symbols, heard, pre.sample, aligned_post, packet_length_, kSymbols, 1, stretch);
  if (!soft) {
    // Lined up beyond any clock we look for: not a packet's two chirps.
    RxEvent ev;
    ev.noise = RxEvent::Noise::kBadCrc;
    ev.start = pre.sample / sample_rate_;
    ev.end = (post.sample + chirp_length_) / sample_rate_;
    ev.level_db = 10.0 * std::log10(pre.power + 1e-20);
    return ev;
  }
  const room_code::DecodedBlock decoded = room_code::DecodeBlock(*soft, kPayloadBits);

  RxEvent ev = Spanning(heard, pre.sample, post.sample);
  ev.quality = 1.0 - static_cast<double>(decoded.corrected) / kCodedBits;
  ev.fixed_bits = decoded.corrected;
  ev.rate_error = 1.0 / stretch - 1.0;
  ev.clarity = std::min(pre.ratio, post.ratio);
  Frame frame{};
  frame[0] = kHeader;
  std::copy(decoded.bytes.begin(), decoded.bytes.end(), frame.begin() + 1);
  if (CrcMatches(frame, crc_)) {
    ev.kind = RxEvent::Kind::kPacket;
    ev.data.assign(frame.begin() + 1, frame.begin() + 1 + kDataBytes);
  } else {
    ev.kind = RxEvent::Kind::kNoise;
    ev.noise = RxEvent::Noise::kBadCrc;
  }
  return ev;
}

std::optional<RoomHeaderFound> RoomPairDecoder::DecodeHeader(RoomSymbolReader& symbols, const SampleRing& heard,
                                                             const ChirpPeak& a, double aligned_b) const {
  double stretch = 1.0;
  const std::optional<std::vector<float>> soft =
      ReadBlock(symbols, heard, a.sample, aligned_b, header_length_, room_frame::kHeaderSymbols, 1, stretch);
  if (!soft) return std::nullopt;
  const room_code::DecodedBlock decoded = room_code::DecodeBlock(*soft, room_frame::kHeaderBits);
  const std::optional<room_frame::Header> header = room_frame::ParseHeader(decoded.bytes);
  // Its CRC-3 and rate field pass one read of noise in ten; a header the code had to correct in
  // more than kMostHeaderCorrections of its 63 coded bits is taken for one of those.
  if (!header || decoded.corrected > kMostHeaderCorrections) return std::nullopt;
  return RoomHeaderFound{*header, stretch, decoded.corrected};
}

RxEvent RoomPairDecoder::DecodePayload(RoomSymbolReader& symbols, const SampleRing& heard, const ChirpPeak& a,
                                       const ChirpPeak& b, const RoomHeaderFound& found, const ChirpPeak& c,
                                       double aligned_c) const {
  const room_frame::Header& header = found.header;
  const int count = room_frame::PayloadSymbols(header.bytes, header.rate);
  const int bits = room_frame::PayloadBits(header.bytes);
  const room_code::BlockShape shape = room_frame::PayloadShape(header.rate);
  RxEvent ev = Spanning(heard, a.sample, c.sample);
  ev.rate = header.rate;
  ev.clarity = std::min({a.ratio, b.ratio, c.ratio});
  double stretch = found.stretch;
  const std::optional<std::vector<float>> soft =
      ReadBlock(symbols, heard, b.sample, aligned_c, PayloadLength(header), count, shape.tones, stretch);
  ev.rate_error = 1.0 / stretch - 1.0;
  ev.noise = RxEvent::Noise::kBadCrc;
  if (!soft) return ev;
  const room_code::DecodedBlock decoded = room_code::DecodeBlock(*soft, bits, shape);
  const int coded = room_code::CodedBits(bits, shape.code) + room_code::CodedBits(room_frame::kHeaderBits);
  ev.fixed_bits = decoded.corrected + found.corrected;
  ev.quality = 1.0 - static_cast<double>(ev.fixed_bits) / coded;
  if (std::optional<std::vector<std::uint8_t>> data = room_frame::CheckedData(header, decoded.bytes)) {
    ev.kind = RxEvent::Kind::kPacket;
    ev.noise = RxEvent::Noise::kNone;
    ev.data = std::move(*data);
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
