// The room profile end to end: its code, its modulator and receiver.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "nava_modem/frame.h"
#include "nava_modem/hop_contrast.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/room_code.h"
#include "nava_modem/room_phy.h"
#include "profile_signals.h"
#include "test_signals.h"

namespace nava_modem {
namespace {

using Payloads = std::vector<std::vector<std::uint8_t>>;
using test_signals::ClockOffset;
using test_signals::Hear;
using test_signals::PacketsOf;
using test_signals::RandomPayloads;

// Packets with gaps between them, as a sender would play them.
std::vector<float> Play(const ModemProfile& profile, const Payloads& payloads, double gap) {
  return test_signals::Train(payloads, static_cast<std::size_t>(gap * profile.options().sample_rate),
                             [&](const auto& p) { return profile.ModulatePacket(p); });
}

TEST(RoomProfile, FitsTheBudget) {
  EXPECT_LE(ProfileAirtime(Profile::kRoom), 2.0);
  const MacTiming t = ProfileTiming(Profile::kRoom);
  EXPECT_GE(t.packet_bits / t.bit_rate, ProfileAirtime(Profile::kRoom));
  EXPECT_LT(t.packet_bits / t.bit_rate, ProfileAirtime(Profile::kRoom) + 1.0 / t.bit_rate);
}

TEST(RoomProfile, RoundTripsAtEachSampleRate) {
  for (double rate : {16000.0, 44100.0, 48000.0}) {
    ModemOptions o;
    o.sample_rate = rate;
    const auto profile = MakeProfile(Profile::kRoom, o);
    const Payloads payloads = RandomPayloads(6, static_cast<unsigned>(rate));
    std::vector<float> audio = Play(*profile, payloads, 0.4);
    EXPECT_NEAR(profile->ModulatePacket(payloads[0]).size() / rate, profile->Airtime(), 1e-3);
    std::mt19937 rng(3);
    std::normal_distribution<float> noise(0.0f, 0.01f);
    for (float& x : audio) x += noise(rng);
    const auto events = Hear(*profile, audio);
    EXPECT_EQ(PacketsOf(events), payloads) << rate << " Hz";
    EXPECT_EQ(events.size(), payloads.size()) << rate << " Hz: no noise reports";
    for (const RxEvent& e : events) EXPECT_NEAR(e.rate_error, 0.0, 1e-4);
  }
}

TEST(RoomProfile, FollowsTheSendersClock) {
  ModemOptions o;
  o.sample_rate = 16000.0;
  const auto profile = MakeProfile(Profile::kRoom, o);
  const Payloads payloads = RandomPayloads(4, 7);
  for (double offset : {-0.01, -0.003, 0.004, 0.01}) {
    const auto events = Hear(*profile, ClockOffset(Play(*profile, payloads, 0.3), offset));
    EXPECT_EQ(PacketsOf(events), payloads) << offset;
    for (const RxEvent& e : events) EXPECT_NEAR(e.rate_error, offset, 2e-4) << offset;
  }
}

// Rooms rendered by nava_room's renderer where the reverberation is louder than the direct
// sound, with noise, a whine and the sender's clock off: a regression band, not a speed test.
// Each condition spreads its packets over three rooms (seeds). The office (pink noise, a whine
// as loud as the packets, a tilted speaker, at 16 kHz) lost 4 of 12 before the chirp detector
// whitened its input by the noise's spectrum.
TEST(RoomProfile, DecodesInReverberantRooms) {
  ModemOptions o;
  o.sample_rate = 16000.0;
  const auto profile = MakeProfile(Profile::kRoom, o);
  struct Condition {
    const char* name;
    RoomOptions room;
  };
  RoomOptions hall;  // RT60 1.0 s, DRR -10 dB
  hall.rt60 = 1.0;
  hall.drr_db = -10.0;
  hall.noise = RoomOptions::Noise::kWhite;
  hall.snr_db = 30.0;
  const RoomOptions office = test_signals::NoisyOffice();
  int decoded = 0, sent = 0;
  for (const Condition& c : {Condition{"hall", hall}, Condition{"office", office}}) {
    for (unsigned room = 0; room < 3; ++room) {
      const Payloads payloads = RandomPayloads(4, 100 + room);
      RoomOptions r = c.room;
      r.seed = 200 + room;
      const auto events = Hear(*profile, RenderRoom(Play(*profile, payloads, 0.6), o.sample_rate, r));
      int here = 0;
      for (const auto& p : PacketsOf(events)) {
        EXPECT_NE(std::find(payloads.begin(), payloads.end(), p), payloads.end()) << c.name << ": a packet never sent";
        here += std::find(payloads.begin(), payloads.end(), p) != payloads.end();
      }
      EXPECT_LE(here, 4) << c.name << ": a packet decoded twice";
      decoded += here;
      sent += 4;
    }
  }
  std::printf("room profile in reverberant rooms: %d of %d packets\n", decoded, sent);
  EXPECT_GE(decoded, sent - 1);  // 24 of 24 when written
}

// A packet whose second chirp never stands out (in a room whose reverberation stands 15-20 dB
// over the direct sound for seconds, its matched-filter peak is one among many as tall) is
// found by its data: the receiver reads the symbols at trial clocks across +-3.5 % and decodes
// where they stand out most in their sub-bands. Before that, each of these was a lone chirp
// (ONE_BYTE) and nothing was decoded.
TEST(RoomProfile, FindsAPacketWhoseSecondChirpIsLostByItsData) {
  ModemOptions o;
  o.sample_rate = 48000.0;
  const auto profile = MakeProfile(Profile::kRoom, o);
  const Payloads payloads = RandomPayloads(4, 31);
  const std::size_t chirp = static_cast<std::size_t>(room_phy::kChirpSeconds * o.sample_rate);
  for (double clock : {0.0, 0.02, -0.03}) {
    std::vector<float> audio = test_signals::Train(payloads, static_cast<std::size_t>(1.0 * o.sample_rate), [&](const auto& p) {
      std::vector<float> burst = profile->ModulatePacket(p);
      std::fill(burst.end() - static_cast<std::ptrdiff_t>(chirp), burst.end(), 0.0f);
      return burst;
    });
    if (clock != 0.0) audio = ClockOffset(audio, clock);
    test_signals::AddNoise(audio, 0.1, 10.0, o.sample_rate, 5, 600.0, 5400.0);
    const auto events = Hear(*profile, audio);
    EXPECT_EQ(PacketsOf(events), payloads) << "clock " << clock;
    for (const RxEvent& e : events) {
      // The clock as far as the data places the second chirp: within a few milliseconds of 1.8 s.
      if (e.kind == RxEvent::Kind::kPacket) {
        EXPECT_NEAR(e.rate_error, clock, 0.003) << "clock " << clock;
      }
    }
  }
}

// A lone chirp in noise (a knock, a word that passed for one) is reported as ONE_BYTE: the data
// search finds no symbols standing out after it, and decodes nothing.
TEST(RoomProfile, ALoneChirpInNoiseIsNoPacket) {
  ModemOptions o;
  o.sample_rate = 48000.0;
  const auto profile = MakeProfile(Profile::kRoom, o);
  for (unsigned seed : {1u, 2u, 3u}) {
    std::vector<float> audio(static_cast<std::size_t>(3.0 * o.sample_rate), 0.0f);
    const std::vector<float> chirp = room_phy::Chirp(o.sample_rate);
    std::transform(chirp.begin(), chirp.end(), audio.begin() + static_cast<std::ptrdiff_t>(audio.size() / 3), audio.begin() + static_cast<std::ptrdiff_t>(audio.size() / 3),
                   [](float c, float a) { return a + 0.3f * c; });
    test_signals::AddNoise(audio, 0.045, 10.0, o.sample_rate, seed, 600.0, 5400.0);
    const auto events = Hear(*profile, audio);
    EXPECT_TRUE(PacketsOf(events).empty()) << "seed " << seed;
    ASSERT_EQ(events.size(), 1u) << "seed " << seed;
    EXPECT_EQ(events[0].noise, RxEvent::Noise::kOneByte);
  }
}

TEST(HopContrast, ScoresSymbolsThatStandOutInTheirSubBands) {
  using namespace room_phy;
  std::vector<double> flat(static_cast<std::size_t>(kSymbols) * kBins, 1.0);
  EXPECT_NEAR(HopContrast(flat), 0.0, 1e-12);
  std::vector<double> sent = flat;
  for (int s = 0; s < kSymbols; ++s) sent[static_cast<std::size_t>(s) * kBins + Bin(s, s % kTonesPerBand) - kLowestBin] = 100.0;
  EXPECT_NEAR(HopContrast(sent), std::log(100.0), 1e-9);
  // With a stride only the symbols it reaches count: a tone in every third symbol alone.
  std::vector<double> thirds = flat;
  for (int s = 0; s < kSymbols; s += 3) thirds[static_cast<std::size_t>(s) * kBins + Bin(s, 0) - kLowestBin] = 100.0;
  EXPECT_NEAR(HopContrast(thirds, 3), std::log(100.0), 1e-9);
  EXPECT_NEAR(HopContrast(thirds), std::log(100.0) / 3.0, 1e-9);
  // A tone outside the symbol's own sub-band counts for nothing.
  std::vector<double> elsewhere = flat;
  for (int s = 0; s < kSymbols; ++s) elsewhere[static_cast<std::size_t>(s) * kBins + (Bin(s, 0) - kLowestBin + kTonesPerBand) % kBins] = 100.0;
  EXPECT_NEAR(HopContrast(elsewhere), 0.0, 1e-12);
  EXPECT_THROW(HopContrast(flat, 0), std::invalid_argument);
  try {
    HopContrast(std::vector<double>(10, 1.0));
    FAIL() << "a wrong size was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("10 tone energies, expected 8064"), std::string::npos) << e.what();
  }
}

TEST(RoomProfile, RefusesARateThatCannotCarryItsBand) {
  ModemOptions o;
  o.sample_rate = 8000.0;
  try {
    MakeProfile(Profile::kRoom, o);
    FAIL() << "8000 Hz accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("8000"), std::string::npos) << e.what();
  }
}

TEST(RoomProfile, ParsesNames) {
  EXPECT_EQ(ParseProfile("nava"), Profile::kNava);
  EXPECT_EQ(ParseProfile("room"), Profile::kRoom);
  EXPECT_FALSE(ParseProfile("Room").has_value());
  EXPECT_STREQ(ProfileName(Profile::kRoom), "room");
}

}  // namespace
}  // namespace nava_modem

namespace nava_modem {
namespace {

// Soft bits for received tones, each as sure as a clear tone makes it.
room_code::SoftBits SoftFor(const room_code::Tones& tones) {
  room_code::SoftBits soft{};
  for (int s = 0; s < room_phy::kSymbols; ++s) {
    const int value = room_code::ToneBits(tones[s]);
    for (int j = 0; j < room_phy::kBitsPerSymbol; ++j) {
      soft[s * room_phy::kBitsPerSymbol + j] = ((value >> (room_phy::kBitsPerSymbol - 1 - j)) & 1) ? 4.0f : -4.0f;
    }
  }
  return soft;
}

// How `wrong` symbols, each replaced by another tone at random, come out of the code: right,
// flagged (the CRC fails: BAD_CRC noise), or wrong (a CRC-passing payload never sent).
struct Outcome {
  int right = 0, flagged = 0, wrong = 0;
};
Outcome Corrupt(int wrong, int trials, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255), symbol(0, room_phy::kSymbols - 1), other(1, room_phy::kTonesPerBand - 1);
  Outcome out;
  for (int t = 0; t < trials; ++t) {
    std::vector<std::uint8_t> data(kDataBytes);
    for (auto& b : data) b = static_cast<std::uint8_t>(byte(rng));
    const Frame frame = MakeFrame(data, CrcVariant::kCcittFalse);
    room_code::Payload payload{};
    std::copy(frame.begin() + 1, frame.end(), payload.begin());
    room_code::Tones tones = room_code::Encode(payload);
    std::vector<int> order(room_phy::kSymbols);
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    for (int k = 0; k < wrong; ++k) tones[order[k]] = (tones[order[k]] + other(rng)) % room_phy::kTonesPerBand;
    const room_code::Decoded decoded = room_code::Decode(SoftFor(tones));
    Frame got{};
    got[0] = kHeader;
    std::copy(decoded.payload.begin(), decoded.payload.end(), got.begin() + 1);
    if (got == frame) {
      ++out.right;
    } else if (CrcMatches(got, CrcVariant::kCcittFalse)) {
      ++out.wrong;
    } else {
      ++out.flagged;
    }
  }
  return out;
}

// The code corrects any 4 wrong symbols of 42 and nearly always 8 (a symbol carries 4 coded
// bits; the K=9 rate-1/3 code's free distance is 18); beyond what it can correct, the CRC
// flags the payload instead of passing a wrong one.
TEST(RoomCode, CorrectsWrongSymbolsAndFlagsTooMany) {
  for (int wrong = 0; wrong <= 4; ++wrong) {
    const Outcome o = Corrupt(wrong, 300, 10 + wrong);
    EXPECT_EQ(o.right, 300) << wrong << " wrong symbols";
  }
  const Outcome eight = Corrupt(8, 300, 18);
  EXPECT_GE(eight.right, 285) << "8 wrong symbols";
  EXPECT_EQ(eight.wrong, 0);
  for (int wrong : {16, 20, 30}) {
    const Outcome o = Corrupt(wrong, 300, 20 + wrong);
    EXPECT_EQ(o.wrong, 0) << wrong << " wrong symbols passed the CRC";
    EXPECT_GT(o.flagged, 0) << wrong << " wrong symbols never flagged";
  }
}

TEST(RoomCode, GrayMapsNeighbouringTonesOneBitApart) {
  for (int tone = 0; tone + 1 < room_phy::kTonesPerBand; ++tone) {
    const int diff = room_code::ToneBits(tone) ^ room_code::ToneBits(tone + 1);
    EXPECT_EQ(diff & (diff - 1), 0) << tone;
  }
}

}  // namespace
}  // namespace nava_modem
