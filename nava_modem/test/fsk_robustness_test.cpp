// The FSK receiver on realistic audio: one tone weaker than the other (speaker, room and
// microphone tilt the spectrum), a reverberant room, a sender whose sound card clock is off.
// The signals are made here (test_signals.h), seeded.
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "nava_modem/fsk_receiver.h"
#include "nava_modem/room_channel.h"
#include "test_signals.h"

namespace nava_modem {
namespace {

using namespace test_signals;

// Packets of `payloads` decoded right from the audio (each at most once); a packet decoded
// wrong fails the test.
int DecodedRight(const ModemOptions& o, const std::vector<float>& audio, const std::vector<std::vector<std::uint8_t>>& payloads) {
  ReceiverOptions ro;
  ro.carrier_threshold_db = -40.0;
  FskReceiver rx(o, ro);
  std::vector<RxEvent> events;
  rx.Process(audio.data(), audio.size(), events);
  rx.Flush(events);
  std::map<std::vector<std::uint8_t>, int> left;
  for (const auto& p : payloads) ++left[p];
  int right = 0;
  for (const RxEvent& e : events) {
    if (e.kind != RxEvent::Kind::kPacket) continue;
    const auto it = left.find(e.data);
    EXPECT_NE(it, left.end()) << "a wrong packet passed the CRC";
    if (it != left.end() && it->second > 0) {
      --it->second;
      ++right;
    }
  }
  return right;
}

// The packets of `payloads` (their train `clean`) decoded right through `response` with white
// noise at `snr_db` (and a tilt), the noise drawn with `noise_seed`.
int DecodedRightThrough(const ModemOptions& o, const std::vector<float>& clean,
                        const std::vector<std::vector<std::uint8_t>>& payloads, std::vector<float> response,
                        double snr_db, unsigned noise_seed, double tilt_db = 0.0) {
  RoomOptions room;
  room.response = std::move(response);
  room.noise = RoomOptions::Noise::kWhite;
  room.snr_db = snr_db;
  room.tilt_db = tilt_db;
  room.seed = noise_seed;
  return DecodedRight(o, RenderRoom(clean, o.sample_rate, room), payloads);
}

// `packets` random packets (payload seed `payload_seed`) through the room `room(seed)` of each of
// `seeds` (noise seed noise_base + seed), decoded right, summed; each room's count printed.
int DecodedRightOverRooms(const ModemOptions& o, int packets, unsigned payload_seed,
                          const std::function<std::vector<float>(unsigned)>& room, const std::vector<unsigned>& seeds,
                          double snr_db, unsigned noise_base, double tilt_db, const char* what) {
  const auto payloads = RandomPayloads(packets, payload_seed);
  const std::vector<float> clean = PacketTrain(o, payloads, 0.5);
  int right = 0;
  for (unsigned seed : seeds) {
    const int here = DecodedRightThrough(o, clean, payloads, room(seed), snr_db, noise_base + seed, tilt_db);
    std::printf("%s, seed %u: %d of %d\n", what, seed, here, packets);
    right += here;
  }
  return right;
}

double TonePower(const ModemOptions& o) { return o.amplitude * o.amplitude / 2.0; }

// One tone weaker than the other by 0 to 20 dB, either way, by a shelf between the tones and
// by a peaking cut at the weaker tone (sox's `equalizer 3700 1000h -12`: this cut once lost
// most packets at 10 to 12 dB yet none at 15, because the clock fit and the decisions
// compared the tones' raw powers). White noise in 2-4 kHz 10 dB below the weaker tone (shelf)
// or 40 dB below it (peaking cut); the level changes from step to step. Every packet must
// decode at every step.
TEST(FskRobustness, TiltSweepHasNoDip) {
  ModemOptions o;
  const int packets = 10;
  int step = 0;
  for (const bool peaking : {false, true}) {
    for (const bool space_weaker : {true, false}) {
      for (int cut = 0; cut <= 20; cut += 2, ++step) {
        const auto payloads = RandomPayloads(packets, 1000 + step);
        std::vector<float> audio = PacketTrain(o, payloads, 0.2);
        if (peaking) {
          if (cut > 0) PeakingEq(space_weaker ? o.space_hz : o.mark_hz, 1000.0, -cut, o.sample_rate).Run(audio);
        } else {
          Tilt(audio, o.mark_hz, o.space_hz, space_weaker ? -cut : cut, o.sample_rate);
        }
        // The shelf tilts the whole band; a narrow cut also weakens and smears the weaker
        // tone's short bits more than its steady tone (its ringing), so it gets cleaner audio:
        // with the noise 30 dB below the louder tone, both we and minimodem lose packets
        // beyond a 16 dB cut.
        AddNoise(audio, TonePower(o) * std::pow(10.0, -cut / 10.0), peaking ? 40.0 : 10.0, o.sample_rate, 2000 + step);
        const float level = static_cast<float>(std::pow(10.0, -(step % 4) * 15.0 / 20.0));  // 0 to -45 dB
        for (float& x : audio) x *= level;
        EXPECT_EQ(DecodedRight(o, audio, payloads), packets)
            << (peaking ? "peaking cut" : "shelf") << ": " << (space_weaker ? "SPACE" : "MARK") << " " << cut << " dB weaker";
      }
    }
  }
}

// A room with RT60 0.3 s and the direct sound 3 dB above the reverberation (nava_room's
// renderer): early reflections 1.5 to 12 bits late and a diffuse tail, which add to each bit's
// tone with the phase of earlier bits. Several rooms, since one room's response at the two
// tones (a random fade of each) decides much.
TEST(FskRobustness, ReverberantRoomDecodesAKnownShare) {
  ModemOptions o;
  const int rooms = 6, packets = 10;
  int right = 0;
  for (int room = 0; room < rooms; ++room) {
    const auto payloads = RandomPayloads(packets, 3000 + room);
    RoomOptions r;
    r.rt60 = 0.3;
    r.drr_db = 3.0;
    r.noise = RoomOptions::Noise::kWhite;
    r.snr_db = 30.0;
    r.seed = 4000 + room;
    right += DecodedRight(o, RenderRoom(PacketTrain(o, payloads, 0.3), o.sample_rate, r), payloads);
  }
  std::printf("RT60 0.3 s, DRR +3 dB: %d of %d packets decoded\n", right, rooms * packets);
  // 50 when written (the receiver before the equaliser, FskEqualizer: 9; minimodem: 0).
  EXPECT_GE(right, 46);
  EXPECT_LE(right, rooms * packets);
}

// The equaliser is not tuned to the rooms above: six other rooms at RT60 0.3 s, DRR +3 dB, and
// the rooms above with a longer tail (RT60 0.5 s).
TEST(FskRobustness, OtherReverberantRoomsDecodeAKnownShare) {
  ModemOptions o;
  const int rooms = 6, packets = 10;
  int right[2] = {0, 0};
  for (int condition = 0; condition < 2; ++condition) {
    for (int room = 0; room < rooms; ++room) {
      const unsigned seed = condition == 0 ? 5000 + room : 4000 + room;
      const auto payloads = RandomPayloads(packets, seed - 1000);
      RoomOptions r;
      r.rt60 = condition == 0 ? 0.3 : 0.5;
      r.drr_db = 3.0;
      r.noise = RoomOptions::Noise::kWhite;
      r.snr_db = 30.0;
      r.seed = seed;
      right[condition] += DecodedRight(o, RenderRoom(PacketTrain(o, payloads, 0.3), o.sample_rate, r), payloads);
    }
  }
  std::printf("RT60 0.3 s, other rooms: %d of %d; RT60 0.5 s: %d of %d\n", right[0], rooms * packets, right[1], rooms * packets);
  // 32 and 50 when written (before the equaliser: 6 and 4).
  EXPECT_GE(right[0], 28);
  EXPECT_GE(right[1], 46);
}

// The sender's sound card 1 % fast or slow: tones and bit rate scaled alike.
TEST(FskRobustness, ClockOffsetOfOnePercentDecodes) {
  for (const double sample_rate : {16000.0, 48000.0}) {
    ModemOptions o;
    o.sample_rate = sample_rate;
    for (const double error : {-0.01, 0.01}) {
      const auto payloads = RandomPayloads(10, 6000);
      std::vector<float> audio = PacketTrain(o, payloads, 0.2, error);
      AddNoise(audio, TonePower(o), 10.0, o.sample_rate, 7000);
      EXPECT_EQ(DecodedRight(o, audio, payloads), 10) << "clock error " << error << " at " << sample_rate << " Hz";
    }
  }
}

// What made the thesis's FSK fail in measured rooms whose direct sound dominates (a teaching
// room's far ear, a concert hall's front seats, and homes and basements at DRR +7 to +12 dB),
// rendered here: a strong reflection within a bit (0.7 of the direct sound, 0.217 ms late, so
// that it cancels MARK at 2300 Hz and adds to SPACE: MARK about 13 dB below SPACE) and a
// reverberant tail (RT60 0.5 s) 8 dB below the direct sound. SPACE's tail then outweighs
// MARK's direct sound in any sum of the two tones, which hid every packet's break from the
// detector (0 of 12 before the detector saw the step tone by tone); the CRC must pass no
// wrong packet.
// Adds to `h` a diffuse tail: Gaussian noise from `from` s after the direct sound (at sample
// `direct`, of energy 1) on, decaying by 60 dB in `rt60`, scaled so that its energy from
// `counted_from` s on is `energy`.
void AddDiffuseTail(std::vector<float>& h, std::size_t direct, double rate, double from, double rt60, double counted_from,
                    double energy, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> tail(h.size(), 0.0);
  double counted = 0.0;
  for (std::size_t n = direct + static_cast<std::size_t>(from * rate); n < h.size(); ++n) {
    tail[n] = gauss(rng) * std::exp(-6.9078 * static_cast<double>(n - direct) / rate / rt60);
    if (n >= direct + static_cast<std::size_t>(counted_from * rate)) counted += tail[n] * tail[n];
  }
  const double scale = std::sqrt(energy / counted);
  for (std::size_t n = 0; n < h.size(); ++n) h[n] += static_cast<float>(scale * tail[n]);
}

std::vector<float> StrongToneWeakToneRoom(double sample_rate, double drr_db, unsigned seed) {
  std::vector<float> h(static_cast<std::size_t>(0.6 * sample_rate), 0.0f);
  const std::size_t direct = static_cast<std::size_t>(0.005 * sample_rate);
  h[direct] = 1.0f;
  // The reflection at a fractional delay: a windowed sinc.
  const double at = static_cast<double>(direct) + 0.000217 * sample_rate;
  for (int k = -16; k <= 16; ++k) {
    const std::size_t n = static_cast<std::size_t>(std::floor(at) + k);
    const double x = static_cast<double>(n) - at;
    const double sinc = std::abs(x) < 1e-9 ? 1.0 : std::sin(M_PI * x) / (M_PI * x);
    const double window = 0.5 + 0.5 * std::cos(M_PI * x / 17.0);
    h[n] += static_cast<float>(0.7 * sinc * window);
  }
  AddDiffuseTail(h, direct, sample_rate, 0.003, 0.5, 0.003, (1.0 + 0.49) * std::pow(10.0, -drr_db / 10.0), seed);
  return h;
}

TEST(FskRobustness, AToneCancelledByAReflectionWithinABitAndAReverberantTail) {
  ModemOptions o;
  const auto payloads = RandomPayloads(12, 77);
  const std::vector<float> clean = PacketTrain(o, payloads, 0.5);
  for (const double snr : {20.0, 3.0}) {
    const int right = DecodedRightThrough(o, clean, payloads, StrongToneWeakToneRoom(o.sample_rate, 8.0, 5), snr, 9);
    EXPECT_GE(right, 11) << "white noise at SNR " << snr << " dB";
  }
}

// The other mechanism of the measured rooms that failed (a teaching room's near ear, DRR 0 to
// +2 dB): discrete early reflections a few bits late (1.3 to 23 ms, 6 to 16 dB below the direct
// sound), as a wall, a table and the floor give. They pulled the clock fit one or two bits late
// and left the equaliser's first fit, on the break and the header alone, overfitted: 0 of 12
// packets before (every SNR), all 12 now.
TEST(FskRobustness, DiscreteEarlyReflectionsAFewBitsLate) {
  ModemOptions o;
  const auto payloads = RandomPayloads(12, 78);
  const std::vector<float> clean = PacketTrain(o, payloads, 0.5);
  std::vector<float> h(static_cast<std::size_t>(0.1 * o.sample_rate), 0.0f);
  const std::size_t direct = static_cast<std::size_t>(0.02 * o.sample_rate);
  h[direct] = 1.0f;
  const double reflections[][2] = {{1.3, -0.5}, {4.1, 0.35}, {7.6, -0.3}, {11.2, 0.25}, {16.5, -0.2}, {23.0, 0.15}};
  for (const auto& r : reflections) h[direct + static_cast<std::size_t>(std::lround(r[0] * 1e-3 * o.sample_rate))] += static_cast<float>(r[1]);
  for (const double snr : {20.0, 3.0}) {
    EXPECT_GE(DecodedRightThrough(o, clean, payloads, h, snr, 11), 11) << "white noise at SNR " << snr << " dB";
  }
}

// The mechanism of the measured teaching room's -80 degree head, left ear (DRR +0.2 dB): two
// strong reflections 1.5 and 2.25 bits late (5 and 7.5 ms, 8 dB below the direct sound, as its
// response shows), weaker ones within 20 ms, and a tail 6 dB below the direct sound after 40
// ms. The clock that best explains the known bits was then often one or two bits late, or a
// few percent fast, and the equaliser, reading the packet on that clock, failed: with these
// three tails 10 of 36 before it read on the nominal rate around the break, 33 now. (Some
// tails, seeds 2, 3 and 8, leave both at 0 of 12: a mechanism not understood yet.)
std::vector<float> EchoesTwoBitsLateRoom(double rate, unsigned seed) {
  std::vector<float> h(static_cast<std::size_t>(0.8 * rate), 0.0f);
  const std::size_t direct = static_cast<std::size_t>(0.02 * rate);
  h[direct] = 1.0f;
  const double reflections[][2] = {{1.0, 0.15}, {2.0, 0.18}, {5.0, 0.39}, {7.5, -0.37}, {8.0, -0.2}, {12.0, 0.13}, {19.0, -0.13}};
  for (const auto& r : reflections) h[direct + static_cast<std::size_t>(std::lround(r[0] * 1e-3 * rate))] += static_cast<float>(r[1]);
  AddDiffuseTail(h, direct, rate, 0.01, 0.57, 0.04, std::pow(10.0, -6.0 / 10.0), seed);
  return h;
}

TEST(FskRobustness, StrongEchoesTwoBitsLateDoNotTakeTheEqualiserWithTheClock) {
  ModemOptions o;
  const auto room = [&](unsigned seed) { return EchoesTwoBitsLateRoom(o.sample_rate, seed); };
  EXPECT_GE(DecodedRightOverRooms(o, 12, 79, room, {1u, 5u, 6u}, 20.0, 12, 0.0, "echoes two bits late"), 30) << "of 36";
}

// The mechanisms of the measured concert hall's front seat (DRR +4.5 dB, RT60 1.7 s; 18 of 20
// in white noise at 0 dB before): its tail lies beyond the equaliser's 20-bit reach, so the bits
// of the frame's second half keep a residual 6-7 dB under the signal whatever the noise, and a
// packet's only errors are a few bits the search weighed as one event, or the last few bits,
// which no merge of the search ever challenged (they were reported as sure as can be, so the
// two-bit repair never tried them). A tail of our own, as long and as loud.
std::vector<float> LongTailRoom(double rate, double drr_db, double rt60, unsigned seed) {
  std::vector<float> h(static_cast<std::size_t>(1.2 * rt60 * rate), 0.0f);
  const std::size_t direct = static_cast<std::size_t>(0.01 * rate);
  h[direct] = 1.0f;
  AddDiffuseTail(h, direct, rate, 0.0025, rt60, 0.0025, std::pow(10.0, -drr_db / 10.0), seed);
  return h;
}

TEST(FskRobustness, ATailBeyondTheEqualisersReachLeavesOnlyEventsToRepair) {
  // DRR +3 dB, SPACE 8 dB weaker (the speaker's and room's colouring), white noise at 0 dB:
  // 99 of 120 before, 111 with the last bits' reliabilities and the event repairs.
  ModemOptions o;
  int right = 0;
  for (double rt60 : {1.7, 2.5}) {
    const auto room = [&](unsigned seed) { return LongTailRoom(o.sample_rate, 3.0, rt60, seed); };
    right += DecodedRightOverRooms(o, 20, 80, room, {1u, 2u, 3u}, 0.0, 20, -8.0, "tail beyond the equaliser");
  }
  EXPECT_GE(right, 108) << "of 120";
}

// The mechanism of the measured seminar room's dummy-head clap made drier (DRR +4 dB): a first
// arrival bits before the loudest one (11 ms there) and 9 dB under it. The break then looks some
// 6 bits late against the loudest arrival and more against the first, beyond the 5 bits earlier
// the equaliser used to read the packet at. Here 15 ms (4.5 bits): 42 of 60 before, 59 now.
// (At 11 ms, or with the first arrival 3-6 dB under the loudest, one tail of three still
// decodes nothing, before and now: a mechanism not understood yet.)
std::vector<float> EarlyFirstArrivalRoom(double rate, unsigned seed) {
  std::vector<float> h(static_cast<std::size_t>(0.8 * rate), 0.0f);
  const std::size_t first = static_cast<std::size_t>(0.01 * rate);
  const std::size_t loudest = first + static_cast<std::size_t>(std::lround(0.015 * rate));
  h[first] = static_cast<float>(std::pow(10.0, -9.0 / 20.0));
  h[loudest] = 1.0f;
  AddDiffuseTail(h, loudest, rate, 0.0025, 0.6, 0.0025, std::pow(10.0, -4.0 / 10.0), seed);
  return h;
}

TEST(FskRobustness, AFirstArrivalBitsBeforeTheLoudestIsReadFrom) {
  ModemOptions o;
  const auto room = [&](unsigned seed) { return EarlyFirstArrivalRoom(o.sample_rate, seed); };
  EXPECT_GE(DecodedRightOverRooms(o, 20, 81, room, {1u, 2u, 3u}, 20.0, 30, 0.0, "first arrival 4.5 bits early"), 55)
      << "of 60";
}

// The mechanism of a concert hall's far seat and a museum basement made drier (DRR +4 to +8 dB):
// a reflection in opposite phase to SPACE some 10 bits after the direct sound. While SPACE
// sounds it cancels most of it; when SPACE stops it rings on alone for those 10 bits, louder than
// the cancelled tone was, so SPACE's sound falls, then rises, then falls again at the true break
// plus the reflection's delay. The detector took the first fall for the break, 9 or 10 bits
// early, beyond the wide search, which looked only early: 21 of 60 (1, 0, 20), 59 now.
std::vector<float> OppositeReflectionRoom(double rate, double space_hz, unsigned seed) {
  std::vector<float> h(static_cast<std::size_t>(0.8 * rate), 0.0f);
  const std::size_t direct = static_cast<std::size_t>(0.005 * rate);
  h[direct] = 1.0f;
  // A whole number of SPACE's periods late (about 33 ms), inverted: opposite phase at SPACE.
  const std::size_t late = direct + static_cast<std::size_t>(std::lround(122.0 / space_hz * rate));
  h[late] = -0.8f;
  AddDiffuseTail(h, direct, rate, 0.0025, 0.6, 0.0025, std::pow(10.0, -6.0 / 10.0), seed);
  return h;
}

TEST(FskRobustness, ADipInSpaceBitsBeforeTheBreakIsNotTakenForIt) {
  ModemOptions o;
  const auto room = [&](unsigned seed) { return OppositeReflectionRoom(o.sample_rate, o.space_hz, seed); };
  EXPECT_GE(DecodedRightOverRooms(o, 20, 82, room, {1u, 2u, 3u}, 20.0, 40, 9.0, "SPACE dipped 10 bits before the break"), 55)
      << "of 60";
}

}  // namespace
}  // namespace nava_modem
