// The room profile's frames of any length (room_frame.h): the header, blocks of any size, and
// long frames through the modulator and receiver, clean, off-clock and in reverberant rooms.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "nava_modem/modem_profile.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/room_code.h"
#include "nava_modem/room_frame.h"
#include "nava_modem/room_phy.h"
#include "profile_signals.h"

namespace nava_modem {
namespace {

using namespace test_signals;  // Hear, PacketsOf, ClockOffset, NoisyOffice
using Payloads = std::vector<std::vector<std::uint8_t>>;

std::vector<std::uint8_t> RandomBytes(int count, std::mt19937& rng) {
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::uint8_t> out(static_cast<std::size_t>(count));
  for (auto& b : out) b = static_cast<std::uint8_t>(byte(rng));
  return out;
}

std::vector<float> Play(const ModemProfile& profile, const Payloads& payloads, double gap, int rate = 0) {
  const std::size_t silence = static_cast<std::size_t>(gap * profile.options().sample_rate);
  std::vector<float> audio(silence, 0.0f);
  for (const auto& p : payloads) {
    const std::vector<float> frame = profile.Modulate(p, rate);
    audio.insert(audio.end(), frame.begin(), frame.end());
    audio.insert(audio.end(), silence, 0.0f);
  }
  return audio;
}

void AddNoise(std::vector<float>& audio, float sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma);
  for (float& x : audio) x += noise(rng);
}

std::unique_ptr<ModemProfile> Room(double sample_rate) {
  ModemOptions o;
  o.sample_rate = sample_rate;
  return MakeProfile(Profile::kRoom, o);
}

TEST(RoomFrame, HeaderRoundTripsAndRefusesEverySingleBitError) {
  for (int bytes = room_frame::kMinBytes; bytes <= room_frame::kMaxBytes; ++bytes) {
    const room_frame::Header header{0, bytes};
    const std::vector<std::uint8_t> bits = room_frame::HeaderBytes(header);
    ASSERT_EQ(bits.size(), 2u);
    EXPECT_EQ(bits[1] & 0x07, 0) << "13 bits, the rest 0";
    const std::optional<room_frame::Header> parsed = room_frame::ParseHeader(bits);
    ASSERT_TRUE(parsed) << bytes;
    EXPECT_EQ(*parsed, header);
    for (int k = 0; k < room_frame::kHeaderBits; ++k) {
      std::vector<std::uint8_t> damaged = bits;
      damaged[static_cast<std::size_t>(k / 8)] ^= static_cast<std::uint8_t>(0x80 >> (k % 8));
      EXPECT_FALSE(room_frame::ParseHeader(damaged)) << bytes << " bytes, bit " << k << " flipped";
    }
  }
  for (int rate = 0; rate < room_frame::kRates; ++rate) {
    EXPECT_EQ(room_frame::ParseHeader(room_frame::HeaderBytes({rate, 64})), (room_frame::Header{rate, 64}));
  }
  // A rate the ladder lacks, with a good CRC-3, is no header.
  std::vector<std::uint8_t> bits = room_frame::HeaderBytes({room_frame::kRateFieldValues - 1, 9});
  EXPECT_FALSE(room_frame::ParseHeader(bits));
}

TEST(RoomFrame, PayloadCrcCoversTheHeader) {
  std::mt19937 rng(5);
  const std::vector<std::uint8_t> data = RandomBytes(20, rng);
  const room_frame::Header header{0, 20};
  const std::vector<std::uint8_t> block = room_frame::PayloadBytes(header, data);
  ASSERT_EQ(block.size(), 24u);
  EXPECT_EQ(room_frame::CheckedData(header, block), data);
  EXPECT_NE(room_frame::FrameCrc(header, data), room_frame::FrameCrc({0, 21}, data));
  std::vector<std::uint8_t> damaged = block;
  damaged[3] ^= 0x10;
  EXPECT_FALSE(room_frame::CheckedData(header, damaged));
  EXPECT_FALSE(room_frame::CheckedData({0, 19}, block)) << "a block of another length";
}

TEST(RoomCode, BlocksOfAnySizeRoundTripThroughWrongSymbols) {
  std::mt19937 rng(11);
  for (int bits : {1, 7, 13, 48, 72, 200, 8 * 255 + 32}) {
    const int symbols = room_code::BlockSymbols(bits) + (bits % 2);  // some with a spare symbol
    const std::vector<std::uint8_t> bytes = RandomBytes((bits + 7) / 8, rng);
    const std::vector<int> tones = room_code::EncodeBlock(bytes, bits, symbols);
    ASSERT_EQ(static_cast<int>(tones.size()), symbols);
    // Soft decisions for the tones sent, with one symbol in 12 replaced by a confident wrong one.
    std::vector<float> soft(static_cast<std::size_t>(symbols) * room_phy::kBitsPerSymbol);
    std::uniform_int_distribution<int> tone(0, room_phy::kTonesPerBand - 1);
    for (int s = 0; s < symbols; ++s) {
      const int sent = s % 12 == 5 ? tone(rng) : tones[static_cast<std::size_t>(s)];
      for (int j = 0; j < room_phy::kBitsPerSymbol; ++j) {
        const bool one = (room_code::ToneBits(sent) >> (room_phy::kBitsPerSymbol - 1 - j)) & 1;
        soft[static_cast<std::size_t>(s * room_phy::kBitsPerSymbol + j)] = one ? 3.0f : -3.0f;
      }
    }
    const room_code::DecodedBlock decoded = room_code::DecodeBlock(soft, bits);
    std::vector<std::uint8_t> expected = bytes;
    if (bits % 8) expected.back() &= static_cast<std::uint8_t>(0xFF << (8 - bits % 8));
    EXPECT_EQ(decoded.bytes, expected) << bits << " bits";
  }
  EXPECT_THROW(room_code::EncodeBlock({1, 2}, 16, room_code::BlockSymbols(16) - 1), std::invalid_argument);
  EXPECT_THROW(room_code::EncodeBlock({1}, 16, 20), std::invalid_argument);
  EXPECT_THROW(room_code::DecodeBlock(std::vector<float>(8), 16), std::invalid_argument);
}

TEST(RoomFrame, AirtimeGrowsWithLengthAndTodaysPacketKeepsItsOwn) {
  EXPECT_DOUBLE_EQ(room_frame::FrameSeconds(4, 0), room_phy::kPacketSeconds);
  double last = 0.0;
  for (int bytes : {1, 2, 3, 5, 64, 255}) {
    const double s = room_frame::FrameSeconds(bytes, 0);
    EXPECT_GT(s, last) << bytes;
    last = s;
    EXPECT_NEAR(room_frame::PayloadPairSeconds(bytes, 0),
                room_phy::kChirpSeconds + room_code::BlockSymbols(8 * bytes + 32) * room_phy::kSymbolSeconds, 1e-12);
  }
  const auto profile = Room(16000.0);
  for (int bytes : {1, 64}) {
    const std::vector<float> frame = profile->Modulate(std::vector<std::uint8_t>(static_cast<std::size_t>(bytes), 1), 0);
    EXPECT_NEAR(frame.size() / 16000.0, profile->Airtime(static_cast<std::size_t>(bytes), 0), 1e-3) << bytes;
  }
  EXPECT_THROW(profile->Modulate({}), std::invalid_argument);
}

TEST(RoomFrame, EveryLengthAndRateRoundTripsBesideTodaysPackets) {
  const auto profile = Room(16000.0);
  std::mt19937 rng(21);
  for (int rate = 0; rate < room_frame::kRates; ++rate) {
    Payloads sent;
    for (int bytes : {1, 4, 2, 3, 5, 4, 17, 64, 8}) sent.push_back(RandomBytes(bytes, rng));
    std::vector<float> audio = Play(*profile, sent, 0.3, rate);
    AddNoise(audio, 0.02f, 3);
    const std::vector<RxEvent> events = Hear(*profile, audio);
    EXPECT_EQ(PacketsOf(events), sent) << "rate " << rate;
    EXPECT_EQ(events.size(), sent.size()) << "rate " << rate << ": no noise reports";
    // Today's packet is sent as before whatever the rate asked: it is the robust step's.
    for (std::size_t k = 0; k < events.size() && k < sent.size(); ++k) {
      EXPECT_EQ(events[k].rate, room_frame::IsPacket(static_cast<int>(sent[k].size()), rate) ? 0 : rate) << k;
    }
  }
}

TEST(RoomFrame, FasterRatesAreShorter) {
  double last = 1e9;
  for (int rate = 0; rate < room_frame::kRates; ++rate) {
    const double s = room_frame::FrameSeconds(64, rate);
    EXPECT_LT(s, last) << rate;
    last = s;
    std::printf("rate %d %s: 64 bytes in %.2f s (%.0f bit/s), 4 bytes in %.2f s\n", rate, room_frame::RateName(rate), s,
                512.0 / s, room_frame::FrameSeconds(4, rate));
  }
  EXPECT_STREQ(room_frame::RateName(room_frame::kRates), "?");
}

TEST(RoomFrame, TheLongestFrameRoundTrips) {
  const auto profile = Room(16000.0);
  std::mt19937 rng(4);
  const Payloads sent = {RandomBytes(255, rng)};
  std::vector<float> audio = Play(*profile, sent, 0.5);
  AddNoise(audio, 0.02f, 9);
  const std::vector<RxEvent> events = Hear(*profile, audio);
  EXPECT_EQ(PacketsOf(events), sent);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NEAR(events[0].end - events[0].start, room_frame::FrameSeconds(255, 0), 0.01);
}

TEST(RoomFrame, FollowsTheSendersClock) {
  const auto profile = Room(16000.0);
  std::mt19937 rng(8);
  int rate = 0;
  for (double offset : {-0.03, 0.012, 0.034}) {
    const Payloads sent = {RandomBytes(64, rng), RandomBytes(9, rng)};
    rate = (rate + 1) % room_frame::kRates;
    std::vector<float> audio = ClockOffset(Play(*profile, sent, 0.4, rate), offset);
    AddNoise(audio, 0.02f, 2);
    const std::vector<RxEvent> events = Hear(*profile, audio);
    EXPECT_EQ(PacketsOf(events), sent) << offset;
    // (Within 0.05 %: the faster rates' short payloads measure the clock over less than a second.)
    for (const RxEvent& e : events) EXPECT_NEAR(e.rate_error, offset, 5e-4) << offset;
  }
}

TEST(RoomFrame, DecodesInReverberantRooms) {
  const double fs = 16000.0;
  const auto profile = Room(fs);
  RoomOptions hall;
  hall.rt60 = 1.0;
  hall.drr_db = -10.0;
  hall.noise = RoomOptions::Noise::kWhite;
  hall.snr_db = 20.0;
  const RoomOptions office = NoisyOffice();
  // The fast step sounds six sub-bands at once, each resting one symbol between uses: it is for
  // small, dry rooms (a link chooses it where it is predicted to deliver), not halls.
  RoomOptions small = hall;
  small.rt60 = 0.3;
  small.drr_db = 3.0;
  small.snr_db = 10.0;
  small.clock_offset = -0.01;
  std::mt19937 rng(30);
  for (int rate = 0; rate < room_frame::kRates; ++rate) {
    int decoded = 0, sent_count = 0;
    const std::vector<RoomOptions> rooms = rate < 2 ? std::vector<RoomOptions>{hall, office} : std::vector<RoomOptions>{small};
    for (const RoomOptions& base : rooms) {
      for (unsigned room = 0; room < 2; ++room) {
        const Payloads sent = {RandomBytes(64, rng), RandomBytes(3, rng)};
        RoomOptions r = base;
        r.seed = 40 + room;
        const Payloads heard = PacketsOf(Hear(*profile, RenderRoom(Play(*profile, sent, 0.6, rate), fs, r)));
        for (const auto& p : heard) {
          EXPECT_NE(std::find(sent.begin(), sent.end(), p), sent.end()) << "a frame never sent";
        }
        decoded += static_cast<int>(heard.size());
        sent_count += static_cast<int>(sent.size());
      }
    }
    std::printf("rate %d frames in %s: %d of %d\n", rate, rate < 2 ? "a hall and an office" : "a small room", decoded, sent_count);
    EXPECT_GE(decoded, sent_count - 1) << "rate " << rate;
  }
}

// A header read as another length puts chirp C where it is not, and the CRC-32 covers the header:
// a damaged length is never a frame, however the rest decodes; what was heard is noise.
TEST(RoomFrame, ADamagedLengthIsNeverAFrame) {
  const double fs = 16000.0;
  const auto profile = Room(fs);
  std::mt19937 rng(12);
  const std::vector<std::uint8_t> data = RandomBytes(10, rng);
  for (int claimed : {9, 11, 12}) {
    std::vector<float> frame = profile->Modulate(data, 0);
    // The header block (chirp A and the header's symbols) of a frame of `claimed` bytes.
    const std::vector<float> other = profile->Modulate(std::vector<std::uint8_t>(static_cast<std::size_t>(claimed), 0), 0);
    const std::size_t header_end = static_cast<std::size_t>(std::lround(room_frame::HeaderPairSeconds() * fs));
    std::copy(other.begin(), other.begin() + static_cast<std::ptrdiff_t>(header_end), frame.begin());
    std::vector<float> audio(static_cast<std::size_t>(0.3 * fs), 0.0f);
    audio.insert(audio.end(), frame.begin(), frame.end());
    audio.insert(audio.end(), static_cast<std::size_t>(fs), 0.0f);
    AddNoise(audio, 0.01f, 6);
    const std::vector<RxEvent> events = Hear(*profile, audio);
    EXPECT_TRUE(PacketsOf(events).empty()) << claimed << " claimed";
    // Reported as noise: its chirps, each alone (the receiver reports a frame that does not decode
    // as it would have heard it had the frame not begun).
    EXPECT_GE(std::count_if(events.begin(), events.end(), [](const RxEvent& e) { return e.kind == RxEvent::Kind::kNoise; }), 2)
        << claimed;
  }
}

}  // namespace
}  // namespace nava_modem
