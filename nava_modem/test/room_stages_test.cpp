// The room receiver's stages alone: the ring of samples heard, the symbol reader and the soft
// bits, the chirps' alignment and the faint-chirp search, the pair decoder, the data search, the
// arrival timing and the carrier sense, on packets whose answer is known.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/chirp_alignment.h"
#include "nava_modem/chirp_detector.h"
#include "nava_modem/frame.h"
#include "nava_modem/hop_contrast.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/room_arrival.h"
#include "nava_modem/room_carrier_sense.h"
#include "nava_modem/room_code.h"
#include "nava_modem/room_data_search.h"
#include "nava_modem/room_modulator.h"
#include "nava_modem/room_pair_decoder.h"
#include "nava_modem/room_phy.h"
#include "nava_modem/room_soft_bits.h"
#include "nava_modem/room_symbol_reader.h"
#include "nava_modem/sample_ring.h"
#include "test_signals.h"

namespace nava_modem {
namespace {

using namespace room_phy;

constexpr double kRate = 16000.0;
const std::vector<std::uint8_t> kData = {0x12, 0x34, 0xAB, 0xCD};

// `data` as the room profile sends it, `lead` samples of silence before and a second after.
std::vector<float> PacketAt(std::size_t lead, const std::vector<std::uint8_t>& data = kData) {
  ModemOptions o;
  o.sample_rate = kRate;
  const std::vector<float> packet = RoomModulator(o).ModulatePacket(data);
  std::vector<float> audio(lead, 0.0f);
  audio.insert(audio.end(), packet.begin(), packet.end());
  audio.resize(audio.size() + static_cast<std::size_t>(kRate), 0.0f);
  return audio;
}

SampleRing Heard(const std::vector<float>& audio) {
  SampleRing ring(static_cast<double>(audio.size()));
  for (float s : audio) ring.Push(s);
  return ring;
}

// The chirps the detector found in `audio`, fed in pieces as a sound card would.
std::vector<ChirpPeak> Chirps(ChirpDetector& detector, const std::vector<float>& audio) {
  std::vector<ChirpPeak> peaks;
  for (std::size_t at = 0; at < audio.size(); at += 441) detector.Process(audio.data() + at, std::min<std::size_t>(441, audio.size() - at), peaks);
  return peaks;
}

TEST(SampleRing, KeepsTheLastSamplesByTheirIndex) {
  SampleRing ring(5.0);  // 8 kept
  EXPECT_EQ(ring.size(), 8u);
  EXPECT_EQ(ring[3], 0.0f);  // silence before the first
  for (int n = 0; n < 11; ++n) ring.Push(static_cast<float>(n));
  EXPECT_EQ(ring.count(), 11);
  EXPECT_EQ(ring[10], 10.0f);
  EXPECT_EQ(ring[3], 3.0f);
  EXPECT_EQ(ring[2], 10.0f);  // overwritten: sample 2 lies 8 before sample 10
}

TEST(RoomSymbolReader, ReadsEachSymbolsToneAndTheSoftBitsDecodeIt) {
  const std::size_t lead = 1000;
  const SampleRing heard = Heard(PacketAt(lead));
  RoomSymbolReader symbols(kRate);
  std::vector<double> energy(static_cast<std::size_t>(kSymbols) * kBins, -1.0);
  symbols.Read(heard, static_cast<double>(lead), 1.0, kSymbols, energy, 1);
  // Each symbol's sent tone, full scale in its own window: the strongest of all 192.
  const Frame frame = MakeFrame(kData, CrcVariant::kCcittFalse);
  room_code::Payload payload{};
  std::copy(frame.begin() + 1, frame.end(), payload.begin());
  const room_code::Tones tones = room_code::Encode(payload);
  for (int s = 0; s < kSymbols; ++s) {
    const double* row = &energy[static_cast<std::size_t>(s) * kBins];
    const int strongest = static_cast<int>(std::max_element(row, row + kBins) - row);
    EXPECT_EQ(strongest, Bin(s, tones[static_cast<std::size_t>(s)]) - kLowestBin) << "symbol " << s;
  }
  EXPECT_GT(HopContrast(energy), 2.5);
  const room_code::Decoded decoded = room_code::Decode(RoomSoftBits(energy));
  EXPECT_EQ(decoded.payload, payload);
  EXPECT_EQ(decoded.corrected, 0);

  // With a stride only every k-th row is read.
  std::vector<double> strided(energy.size(), -1.0);
  symbols.Read(heard, static_cast<double>(lead), 1.0, kSymbols, strided, 3);
  EXPECT_EQ(strided[0], energy[0]);
  EXPECT_EQ(strided[static_cast<std::size_t>(kBins)], -1.0);
  EXPECT_EQ(strided[static_cast<std::size_t>(3 * kBins)], energy[static_cast<std::size_t>(3 * kBins)]);
  // In noise, at a clock 3 % off the windows slide off the tones (half a symbol by the 20th).
  std::vector<float> noisy = PacketAt(lead);
  test_signals::AddNoise(noisy, 0.1, 10.0, kRate, 9, 600.0, 5400.0);
  const SampleRing noisy_heard = Heard(noisy);
  symbols.Read(noisy_heard, static_cast<double>(lead), 1.0, kSymbols, energy, 1);
  const double right = HopContrast(energy);
  symbols.Read(noisy_heard, static_cast<double>(lead), 1.03, kSymbols, energy, 1);
  const double off = HopContrast(energy);
  EXPECT_GT(right, 2.5);
  EXPECT_LT(off, 0.5 * right);  // 2.1 against 7.8 when written
}

TEST(RoomSoftBits, EachToneAgainstItsOwnFloor) {
  room_code::Payload payload{};
  for (int k = 0; k < kPayloadBytes; ++k) payload[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(17 * k + 3);
  const room_code::Tones tones = room_code::Encode(payload);
  std::vector<double> energy(static_cast<std::size_t>(kSymbols) * kBins, 1.0);
  for (int s = 0; s < kSymbols; ++s) energy[static_cast<std::size_t>(s) * kBins + Bin(s, tones[static_cast<std::size_t>(s)]) - kLowestBin] = 100.0;
  // A whine 100 times louder than the tones, in one bin through the whole packet: its floor.
  const int whine = Bin(0, (tones[0] + 5) % kTonesPerBand) - kLowestBin;
  for (int s = 0; s < kSymbols; ++s) energy[static_cast<std::size_t>(s) * kBins + whine] = 1e4;
  const room_code::SoftBits soft = RoomSoftBits(energy);
  for (int s = 0; s < kSymbols; ++s) {
    const int bits = room_code::ToneBits(tones[static_cast<std::size_t>(s)]);
    for (int j = 0; j < kBitsPerSymbol; ++j) {
      const bool one = bits & (1 << (kBitsPerSymbol - 1 - j));
      // log(1 + 100) for the sent tone's side against log(1 + 1) for the other's at best.
      const float v = soft[static_cast<std::size_t>(s * kBitsPerSymbol + j)];
      EXPECT_NEAR(std::abs(v), std::log(101.0) - std::log(2.0), 1e-5) << "symbol " << s << " bit " << j;
      EXPECT_EQ(v > 0.0f, one) << "symbol " << s << " bit " << j;
    }
  }
  EXPECT_EQ(room_code::Decode(soft).payload, payload);
  EXPECT_THROW(RoomSoftBits(std::vector<double>(10, 1.0)), std::invalid_argument);
}

TEST(ChirpAlignment, LinesUpThePacketsChirpsToAFractionOfASample) {
  // Through a room: the direct sound, and a reflection twice as strong 3 ms later.
  std::vector<float> audio = PacketAt(8000);
  const std::size_t echo = static_cast<std::size_t>(0.003 * kRate);
  std::vector<float> room(audio.size() + echo, 0.0f);
  for (std::size_t k = 0; k < audio.size(); ++k) {
    room[k] += 0.3f * audio[k];
    room[k + echo] += 0.6f * audio[k];
  }
  test_signals::AddNoise(room, 0.1, 20.0, kRate, 3, 600.0, 5400.0);
  const std::vector<float> chirp = Chirp(kRate);
  ChirpDetector detector(chirp, kRate, ChirpDetectorOptions{});
  const std::vector<ChirpPeak> peaks = Chirps(detector, room);
  ASSERT_EQ(peaks.size(), 2u);
  const double distance = kPostChirpStart * kRate;  // 28800 samples
  const std::vector<double> posts = AlignedPosts(detector, kRate, peaks[0], peaks[1]);
  ASSERT_EQ(posts.size(), 3u);  // the two best alignments, then the peaks' own distance
  EXPECT_NEAR(posts[0] - peaks[0].sample, distance, 0.1);
  EXPECT_EQ(posts[2], peaks[1].sample);
  // The runner-up lies at least a millisecond from the best.
  EXPECT_GE(std::abs(posts[1] - posts[0]), 0.001 * kRate - 1e-9);
  // Placed anywhere near, the first chirp's envelope finds the second.
  const std::vector<double> near = LineUpChirp(detector, kRate, peaks[0], peaks[0].sample + distance + 200.0, 0.02, 1);
  ASSERT_EQ(near.size(), 1u);
  EXPECT_NEAR(near[0] - peaks[0].sample, distance, 0.1);
  EXPECT_GE(AlignmentLookahead(kRate), std::llround((kAlignAfterS + kAlignReachS) * kRate));
}

TEST(ChirpAlignment, FindsAChirpTooFaintForTheDetectorWhereItMustBe) {
  // The second chirp 20 dB under the first, in noise: the detector passes it over.
  std::vector<float> audio = PacketAt(8000);
  const std::size_t post = 8000 + static_cast<std::size_t>(kPostChirpStart * kRate);
  const std::size_t chirp_length = Chirp(kRate).size();
  for (std::size_t k = post; k < post + chirp_length; ++k) audio[k] *= 0.1f;
  test_signals::AddNoise(audio, 0.5, 20.0, kRate, 4, 600.0, 5400.0);
  ChirpDetector detector(Chirp(kRate), kRate, ChirpDetectorOptions{});
  const std::vector<ChirpPeak> peaks = Chirps(detector, audio);
  ASSERT_EQ(peaks.size(), 1u);
  const double shortest = kPostChirpStart * kRate * 0.965, longest = kPostChirpStart * kRate * 1.035;
  const std::optional<ChirpPeak> found = StrongestChirpIn(detector, kRate, peaks[0].sample + shortest, peaks[0].sample + longest);
  ASSERT_TRUE(found);
  EXPECT_NEAR(found->sample, static_cast<double>(post), 1.0);
  EXPECT_GE(found->ratio, 4.0);
  EXPECT_LT(found->ratio, ChirpDetectorOptions{}.threshold);
  // Nothing where the envelope is not known yet. (Noise alone passes 4 times its mean somewhere
  // in most windows: the CRC judges what is found.)
  EXPECT_FALSE(StrongestChirpIn(detector, kRate, 1.0, static_cast<double>(detector.computed())));
}

TEST(RoomPairDecoder, DecodesThePacketBetweenItsChirps) {
  const std::size_t lead = 4000;
  const SampleRing heard = Heard(PacketAt(lead));
  const std::size_t chirp_length = Chirp(kRate).size();
  RoomPairDecoder decoder(kRate, chirp_length, 0.045, CrcVariant::kCcittFalse);
  EXPECT_DOUBLE_EQ(decoder.packet_length(), kPostChirpStart * kRate);
  RoomSymbolReader symbols(kRate);
  const ChirpPeak pre{static_cast<double>(lead), 900.0, 0.5}, post{lead + decoder.packet_length(), 800.0, 0.5};
  const RxEvent packet = decoder.Decode(symbols, heard, pre, post, post.sample);
  ASSERT_EQ(packet.kind, RxEvent::Kind::kPacket);
  EXPECT_EQ(packet.data, kData);
  EXPECT_EQ(packet.fixed_bits, 0);
  EXPECT_DOUBLE_EQ(packet.quality, 1.0);
  EXPECT_NEAR(packet.rate_error, 0.0, 1e-12);
  EXPECT_EQ(packet.clarity, 800.0);
  EXPECT_DOUBLE_EQ(packet.start, lead / kRate);
  EXPECT_DOUBLE_EQ(packet.end, (post.sample + chirp_length) / kRate);
  EXPECT_TRUE(std::isnan(packet.arrival));  // the receiver times it
  EXPECT_NEAR(packet.level_db, 20.0 * std::log10(ModemOptions{}.amplitude), 0.2);  // the modulator's tones

  // The payload's CRC under another variant fails: BAD_CRC.
  const RxEvent other = RoomPairDecoder(kRate, chirp_length, 0.045, CrcVariant::kXmodem).Decode(symbols, heard, pre, post, post.sample);
  EXPECT_EQ(other.kind, RxEvent::Kind::kNoise);
  EXPECT_EQ(other.noise, RxEvent::Noise::kBadCrc);
  // Chirps lined up beyond the clocks looked for: BAD_CRC without a decode.
  const RxEvent far = decoder.Decode(symbols, heard, pre, post, pre.sample + 1.05 * decoder.packet_length());
  EXPECT_EQ(far.noise, RxEvent::Noise::kBadCrc);
  EXPECT_DOUBLE_EQ(far.level_db, 10.0 * std::log10(0.5));

  const RxEvent lone = decoder.LoneChirp(pre);
  EXPECT_EQ(lone.kind, RxEvent::Kind::kNoise);
  EXPECT_EQ(lone.noise, RxEvent::Noise::kOneByte);
  EXPECT_DOUBLE_EQ(lone.end - lone.start, chirp_length / kRate);
  EXPECT_EQ(lone.clarity, 900.0);
}

TEST(RoomDataSearch, PlacesAMissingSecondChirpByTheData) {
  const std::size_t lead = 4000;
  std::vector<float> audio = PacketAt(lead);
  const double nominal = kPostChirpStart * kRate;
  const std::size_t chirp_length = Chirp(kRate).size();
  const std::size_t post = lead + static_cast<std::size_t>(nominal);
  std::fill(audio.begin() + static_cast<std::ptrdiff_t>(post), audio.begin() + static_cast<std::ptrdiff_t>(post + chirp_length), 0.0f);
  test_signals::AddNoise(audio, 0.1, 10.0, kRate, 5, 600.0, 5400.0);
  RoomSymbolReader symbols(kRate);
  const std::vector<double> found =
      SearchByData(symbols, Heard(audio), static_cast<double>(lead), nominal, 0.965 * nominal, 1.035 * nominal, chirp_length);
  ASSERT_FALSE(found.empty());
  EXPECT_LE(found.size(), 2u);
  EXPECT_NEAR(found[0], nominal, kDataSearchStepS * kRate);

  // Noise alone after a chirp: no trial scores as a packet.
  std::vector<float> noise(audio.size(), 0.0f);
  test_signals::AddNoise(noise, 0.1, 10.0, kRate, 6, 600.0, 5400.0);
  EXPECT_TRUE(SearchByData(symbols, Heard(noise), static_cast<double>(lead), nominal, 0.965 * nominal, 1.035 * nominal, chirp_length).empty());
  // Nothing is read past what has been heard.
  const std::vector<float> cut(audio.begin(), audio.begin() + static_cast<std::ptrdiff_t>(post));
  EXPECT_TRUE(SearchByData(symbols, Heard(cut), static_cast<double>(lead), nominal, 0.965 * nominal, 1.035 * nominal, chirp_length).empty());
}

TEST(RoomArrival, TimesThePacketByItsChirps) {
  const std::size_t lead = 6000;
  std::vector<float> audio = PacketAt(lead);
  test_signals::AddNoise(audio, 0.5, 30.0, kRate, 7, 600.0, 5400.0);
  const SampleRing heard = Heard(audio);
  RoomArrival arrival(Chirp(kRate), kRate);
  const double post = lead + kPostChirpStart * kRate;
  // A bare delay's leading edge lies about 0.2 ms before the delay (first_arrival.h).
  const double both = arrival.Time(heard, static_cast<double>(lead), post);
  const double first = arrival.Time(heard, static_cast<double>(lead), std::nullopt);
  EXPECT_NEAR(both, lead / kRate, 0.0005);
  EXPECT_NEAR(first, lead / kRate, 0.0005);
  EXPECT_NEAR(both, first, 0.0001);
}

TEST(RoomCarrierSense, ReportsBusyAirWithNoFrame) {
  // Half a second of noise 10 dB over the threshold, from 0.2 s, in a second of silence.
  std::vector<float> audio(static_cast<std::size_t>(kRate), 0.0f);
  std::vector<float> noise(static_cast<std::size_t>(0.5 * kRate), 0.0f);
  test_signals::AddNoise(noise, 1e-3, 0.0, kRate, 8, 600.0, 5400.0);
  std::copy(noise.begin(), noise.end(), audio.begin() + static_cast<std::ptrdiff_t>(0.2 * kRate));
  double quiet_from = 0.0, loudest_db = -400.0;
  const auto run = [&](bool frame_found) {
    RoomCarrierSense sense(kRate);
    sense.SetThreshold(-40.0);
    std::vector<RxEvent> events;
    std::int64_t n = 0, steps = 0;
    for (float x : audio) {
      ++n;
      if (!sense.Push(x)) continue;
      ++steps;
      sense.Step(static_cast<double>(n) / kRate, false, events);
      loudest_db = std::max(loudest_db, sense.level_db());
      if (frame_found && n == static_cast<std::int64_t>(0.4 * kRate)) sense.FrameFound();
    }
    EXPECT_EQ(steps, static_cast<std::int64_t>(audio.size()) / 16);  // every millisecond
    quiet_from = sense.quiet_from();
    return events;
  };
  const std::vector<RxEvent> events = run(false);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].noise, RxEvent::Noise::kZeroByte);
  EXPECT_NEAR(events[0].start, 0.2, 0.005);
  // The level is smoothed over 10 ms: it falls 15 dB to the threshold in about 35 ms.
  EXPECT_GT(events[0].end, 0.7);
  EXPECT_LT(events[0].end, 0.74);
  // Busy air ends a symbol's time after its last loud step.
  EXPECT_NEAR(quiet_from, events[0].end + kSymbolSeconds, 1e-9);
  // -30 dB of noise in 600-5400 Hz reads about 3.5 dB more: the level of a tone of that power
  // (BandLevel), over a band a little wider.
  EXPECT_NEAR(loudest_db, -26.0, 1.5);
  // A frame found in it: nothing to report.
  EXPECT_TRUE(run(true).empty());
}

}  // namespace
}  // namespace nava_modem
