// First arrivals: the leading edge of a response's direct sound, and the arrival of a known sound
// heard through a room, on responses of our own with what measured rooms have (a reflection
// stronger than the direct sound, early reflections within a few ms, a reverberant tail, noise).
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "nava_modem/first_arrival.h"
#include "nava_modem/measured_like_response.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/room_impulse_response.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {
namespace {

constexpr double kRate = 48000.0;

// A unit impulse `delay` samples late, fractional delays by a Hann-windowed sinc.
void AddImpulse(std::vector<float>& h, double delay, double gain) {
  const int half = 32;
  const long centre = std::lround(std::floor(delay));
  for (long k = centre - half; k <= centre + half; ++k) {
    if (k < 0 || k >= static_cast<long>(h.size())) continue;
    const double x = static_cast<double>(k) - delay;
    const double sinc = std::abs(x) < 1e-12 ? 1.0 : std::sin(M_PI * x) / (M_PI * x);
    const double hann = 0.5 + 0.5 * std::cos(M_PI * x / (half + 1));
    h[static_cast<std::size_t>(k)] += static_cast<float>(gain * sinc * hann);
  }
}

std::vector<float> Impulse(double delay, std::size_t length = 4800) {
  std::vector<float> h(length, 0.0f);
  AddImpulse(h, delay, 1.0);
  return h;
}

// A room as measured ones are: the direct sound at `delay` samples, a floor reflection 0.4 ms and a
// wall reflection 1.3 ms after it, a reflection 2 ms after it that is louder than the direct
// sound (a head or an obstacle shadowing the direct way), and a decaying tail from 3 ms.
std::vector<float> HardRoom(double delay, double rt60, unsigned seed) {
  std::vector<float> h(static_cast<std::size_t>(delay + 1.2 * rt60 * kRate), 0.0f);
  AddImpulse(h, delay, 1.0);
  AddImpulse(h, delay + 0.0004 * kRate, -0.7);
  AddImpulse(h, delay + 0.0013 * kRate, 0.6);
  AddImpulse(h, delay + 0.0020 * kRate, 1.5);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 0.03);
  for (std::size_t k = static_cast<std::size_t>(delay + 0.003 * kRate); k < h.size(); ++k) {
    const double t = (static_cast<double>(k) - delay) / kRate;
    h[k] += static_cast<float>(gauss(rng) * std::exp(-6.907755 * t / rt60));
  }
  return h;
}

TEST(LeadingEdgeTest, MovesWithTheDelayToAFractionOfASample) {
  const double base = LeadingEdge(Impulse(1000.0), kRate);
  for (double delay : {1000.25, 1000.5, 1003.75, 1400.0, 2000.125}) {
    const double moved = LeadingEdge(Impulse(delay), kRate) - base;
    EXPECT_NEAR(moved, (delay - 1000.0) / kRate, 1e-6) << delay;
  }
}

TEST(LeadingEdgeTest, ABareDelaysEdgeIsTheBandsRiseBeforeIt) {
  const double edge = LeadingEdge(Impulse(1000.0), kRate);
  EXPECT_LT(edge, 1000.0 / kRate);
  EXPECT_GT(edge, 1000.0 / kRate - 0.00025);
}

TEST(LeadingEdgeTest, IsTheDirectSoundsEvenUnderAStrongerReflection) {
  const double bare = LeadingEdge(Impulse(1000.0), kRate);
  std::vector<float> h = Impulse(1000.0);
  AddImpulse(h, 1000.0 + 0.001 * kRate, 1.8);  // 5 dB louder, 1 ms later
  // Its pulse's low skirt lifts the direct sound's rise a little.
  EXPECT_NEAR(LeadingEdge(h, kRate), bare, 2e-5);
  // 26 dB louder, as round a corner in a reverberant hall: still the direct sound.
  std::vector<float> cornered = Impulse(1000.0);
  AddImpulse(cornered, 1000.0 + 0.002 * kRate, 20.0);
  EXPECT_NEAR(LeadingEdge(cornered, kRate), bare, 2e-5);
  // 50 dB louder: beyond what a direct sound can be under, so the reflection is taken.
  std::vector<float> shadowed = Impulse(1000.0);
  AddImpulse(shadowed, 1000.0 + 0.002 * kRate, 316.0);
  EXPECT_NEAR(LeadingEdge(shadowed, kRate), bare + 0.002, 5e-6);
}

TEST(LeadingEdgeTest, RefusesWhatItCannotMeasure) {
  EXPECT_THROW(LeadingEdge({}, kRate), std::invalid_argument);
  EXPECT_THROW(LeadingEdge(Impulse(100.0), 8000.0), std::invalid_argument);
  EXPECT_TRUE(std::isnan(LeadingEdge(std::vector<float>(4800, 0.0f), kRate)));
}

// The chirp that begins a room packet, heard through `h` with white noise at `snr_db` (full
// band, over the packet's power; none at infinity): its arrival, from a window that begins `before_s` ahead of
// where it starts, against the response's leading edge.
double ArrivalError(const std::vector<float>& h, double snr_db, unsigned seed) {
  const std::unique_ptr<ModemProfile> room = MakeProfile(Profile::kRoom, ModemOptions{});
  std::vector<float> clean(static_cast<std::size_t>(0.3 * kRate), 0.0f);
  const std::vector<float> packet = room->ModulatePacket({1, 2, 3, 4});
  const std::size_t start = clean.size();
  clean.insert(clean.end(), packet.begin(), packet.end());
  clean.resize(clean.size() + static_cast<std::size_t>(0.3 * kRate), 0.0f);
  RoomOptions o;
  o.response = h;
  if (std::isfinite(snr_db)) {
    o.noise = RoomOptions::Noise::kWhite;
    o.snr_db = snr_db;
  }
  o.seed = seed;
  const std::vector<float> heard = RenderRoom(clean, kRate, o);
  const std::vector<float> chirp = room_phy::Chirp(kRate);
  const std::size_t from = start - static_cast<std::size_t>(0.025 * kRate);
  const std::size_t count = chirp.size() + static_cast<std::size_t>(0.025 * kRate + 0.05 * kRate);
  const double arrival = static_cast<double>(from) / kRate + FirstArrival(heard.data() + from, count, chirp, kRate);
  return arrival - (static_cast<double>(start) / kRate + LeadingEdge(h, kRate));
}

TEST(FirstArrivalTest, AChirpThroughABareDelayArrivesAtTheResponsesEdge) {
  for (double delay : {100.0, 333.3, 900.6}) EXPECT_NEAR(ArrivalError(Impulse(delay), INFINITY, 1), 0.0, 5e-6) << delay;
}

TEST(FirstArrivalTest, EarlyReflectionsATailAndNoiseLeaveTheEdgeWithinTensOfMicroseconds) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    for (double snr : {20.0, 10.0, 0.0}) {
      const std::vector<float> h = HardRoom(200.0 + 37.3 * seed, 0.5, seed);
      EXPECT_NEAR(ArrivalError(h, snr, seed), 0.0, 1.5e-5) << "seed " << seed << " snr " << snr;
    }
  }
}

// A direct sound with a faint copy of itself half a millisecond before it, 32 dB down (a
// loudspeaker's pre-ringing; a measured direct sound, widened by the transducers, has its pulse's
// first sidelobe there, up to 4 dB over the band's own -31.5 dB). With the band's sidelobe on
// top it stood right at the rule's 28 dB under the largest: in white noise at 10 dB, 9 packets
// of 10 were timed 0.4 ms early and one on time, as a theatre's, a church's and a sports hall's
// were. It is a sidelobe of the sound after it, whatever the noise: every packet is timed on
// the direct sound.
TEST(FirstArrivalTest, ASidelobeBeforeTheDirectSoundIsNotTakenForItPacketToPacket) {
  std::vector<float> h(static_cast<std::size_t>(0.3 * kRate), 0.0f);
  AddImpulse(h, 1000.0, 1.0);
  AddImpulse(h, 1000.0 - 0.0005 * kRate, 0.025);
  const double direct = LeadingEdge(Impulse(1000.0), kRate);
  EXPECT_NEAR(LeadingEdge(h, kRate), direct, 1e-5);
  double earliest = INFINITY, latest = -INFINITY;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    // Against the direct sound's own edge, not the response's (which the same rule reads).
    const double error = ArrivalError(h, 10.0, seed) + LeadingEdge(h, kRate) - direct;
    EXPECT_NEAR(error, 0.0, 3e-5) << "seed " << seed;
    earliest = std::min(earliest, error);
    latest = std::max(latest, error);
  }
  EXPECT_LT(latest - earliest, 5e-5);
}

// What the room receiver makes of `clean` heard through `h` with white noise at `snr_db`.
std::vector<RxEvent> RoomReceiverHears(const std::vector<float>& clean, const std::vector<float>& h, double snr_db) {
  RoomOptions o;
  o.response = h;
  o.noise = RoomOptions::Noise::kWhite;
  o.snr_db = snr_db;
  const std::vector<float> heard = RenderRoom(clean, kRate, o);
  std::vector<RxEvent> events;
  const auto receiver = MakeProfile(Profile::kRoom, ModemOptions{})->MakeReceiver(ReceiverOptions{});
  receiver->Process(heard.data(), heard.size(), events);
  receiver->Flush(events);
  return events;
}

// Two arrivals 0.44 ms apart, the first 10 dB under the second (a studio's live room): how far
// the envelope dips between them turns on their distance to a fraction of a sample, and in
// white noise it crossed the rule's 3 dB packet to packet, so that the first was the direct
// sound in one packet and a shoulder climbed past in the next, 0.44 ms later (344 us of
// jitter). Whether the first counts now grows with its dip over a dB, and the edge with it: as
// the distance grows by a fiftieth of a sample, the edge may move by a small part of the
// 0.44 ms, never by all of it.
TEST(LeadingEdgeTest, DoesNotJumpBetweenTwoArrivalsAsTheDipBetweenThemGrows) {
  double first = NAN, last = NAN, previous = NAN, largest_step = 0.0;
  for (double apart = 20.5; apart <= 21.5; apart += 0.02) {
    std::vector<float> h(4800, 0.0f);
    AddImpulse(h, 1000.0, std::pow(10.0, -10.0 / 20.0));
    AddImpulse(h, 1000.0 + apart, 1.0);
    const double edge = LeadingEdge(h, kRate);
    if (std::isnan(first)) first = edge;
    if (!std::isnan(previous)) largest_step = std::max(largest_step, std::abs(edge - previous));
    previous = last = edge;
  }
  // Climbed past at one end, the direct sound at the other...
  EXPECT_GT(first - last, 3e-4);
  // ...and in between no step of more than a tenth of the way.
  EXPECT_LT(largest_step, 0.1 * (first - last));
}

// Round a corner the direct sound can be 30 dB under the room's sound and its strong early
// reflections a few milliseconds later (the statistical room: a 5 ms gap, then reflections and
// the tail). Its edge is still found, in noise as well.
TEST(FirstArrivalTest, ADirectSound30DbUnderTheReverberationIsStillFound) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const std::vector<float> room = RoomImpulseResponse(0.5, -30.0, kRate, seed);
    std::vector<float> h(static_cast<std::size_t>(150 + 50 * seed), 0.0f);
    const double delay = static_cast<double>(h.size());
    h.insert(h.end(), room.begin(), room.end());
    const double edge = delay / kRate + LeadingEdge(Impulse(1000.0), kRate) - 1000.0 / kRate;
    EXPECT_NEAR(LeadingEdge(h, kRate), edge, 1e-5) << "seed " << seed;
    EXPECT_NEAR(ArrivalError(h, 20.0, seed), 0.0, 3e-5) << "seed " << seed;
  }
}

// The room receiver looks for the direct sound well before the strongest chirp it heard: here a
// reflection 24 dB louder, 40 ms later.
TEST(FirstArrivalTest, TheRoomReceiverFindsADirectSoundFarBeforeTheStrongestReflection) {
  const std::unique_ptr<ModemProfile> room = MakeProfile(Profile::kRoom, ModemOptions{});
  std::vector<float> h = Impulse(300.0, static_cast<std::size_t>(0.1 * kRate));
  AddImpulse(h, 300.0 + 0.040 * kRate, 16.0);
  std::vector<float> clean(static_cast<std::size_t>(0.5 * kRate), 0.0f);
  const double start = static_cast<double>(clean.size()) / kRate;
  const std::vector<float> packet = room->ModulatePacket({9, 8, 7, 6});
  clean.insert(clean.end(), packet.begin(), packet.end());
  clean.resize(clean.size() + static_cast<std::size_t>(0.5 * kRate), 0.0f);
  const std::vector<RxEvent> events = RoomReceiverHears(clean, h, 20.0);
  ASSERT_EQ(events.size(), 1u);
  ASSERT_EQ(events[0].kind, RxEvent::Kind::kPacket);
  EXPECT_NEAR(events[0].arrival, start + LeadingEdge(h, kRate), 1.5e-5);
  EXPECT_NEAR(LeadingEdge(h, kRate), LeadingEdge(Impulse(300.0), kRate), 1e-5);
}

// Round a corner in a hall: a direct sound 25 dB under a reverberation that builds up over the
// hall's mixing time and peaks 20 to 40 ms after it (measured-like rooms of RT60 1 s at 15 m, as
// the scene renderer makes a corner link). The floor was read over the whole search, from 50 ms
// before the strongest arrival: there the hall's own early sound outnumbered the noise, the
// direct sound fell under that floor, and the edge was read 1 to 37 ms late (the response's own
// edge as well, for two of these rooms). Now the floor is the noise 100 to 120 ms before the
// strongest arrival, and both chirps' responses are added.
TEST(FirstArrivalTest, TheRoomReceiverFindsADirectSound25DbUnderAHallsReverberation) {
  const std::unique_ptr<ModemProfile> room = MakeProfile(Profile::kRoom, ModemOptions{});
  for (const unsigned seed : {1u, 5u, 6u}) {
    ResponseGeometry corner;
    corner.distance_m = 15.0;
    const std::vector<float> hall = MeasuredLikeResponse(1.0, -25.0, kRate, seed, corner);
    std::vector<float> h(200, 0.0f);
    h.insert(h.end(), hall.begin(), hall.end());
    // The direct sound's edge: a response of it alone (the first 2.5 ms of the hall's).
    std::vector<float> direct(h.begin(), h.begin() + 200 + kMeasuredLikeDelay + static_cast<std::ptrdiff_t>(0.0025 * kRate));
    direct.resize(h.size(), 0.0f);
    const double edge = LeadingEdge(direct, kRate);
    EXPECT_NEAR(LeadingEdge(h, kRate), edge, 2e-5) << "seed " << seed;
    std::vector<float> clean(static_cast<std::size_t>(0.5 * kRate), 0.0f);
    const double start = static_cast<double>(clean.size()) / kRate;
    const std::vector<float> packet = room->ModulatePacket({4, 3, 2, static_cast<std::uint8_t>(seed)});
    clean.insert(clean.end(), packet.begin(), packet.end());
    clean.resize(clean.size() + static_cast<std::size_t>(1.5 * kRate), 0.0f);
    std::vector<RxEvent> packets;
    for (const RxEvent& e : RoomReceiverHears(clean, h, 30.0)) {
      if (e.kind == RxEvent::Kind::kPacket) packets.push_back(e);
    }
    ASSERT_EQ(packets.size(), 1u) << "seed " << seed;
    EXPECT_NEAR(packets[0].arrival, start + edge, 5e-5) << "seed " << seed;
  }
}

// Two windows with the same sound through the same room, the second's sound a fraction of a
// sample later in it: timed together they arrive where either does alone, and with their noises
// independent a direct sound one window leaves under the floor is found more often.
TEST(FirstArrivalTest, TwoWindowsTogetherAddUpInPhaseAndStandFurtherOverTheNoise) {
  const std::vector<float> chirp = room_phy::Chirp(kRate);
  const std::size_t lead = static_cast<std::size_t>(kFloorLeadS * kRate);
  const std::size_t count = chirp.size() + lead + static_cast<std::size_t>(0.06 * kRate);
  ArrivalTimer timer(chirp, count, kRate);
  // The direct sound, then a reflection 20 dB over it 20 ms later.
  const auto heard = [&](double delay, double noise, unsigned seed) {
    std::vector<float> h(count, 0.0f);
    AddImpulse(h, delay, 1.0);
    AddImpulse(h, delay + 0.02 * kRate, 10.0);
    std::vector<float> x(count, 0.0f);
    for (std::size_t i = 0; i < count; ++i) {
      if (h[i] == 0.0f) continue;
      for (std::size_t k = 0; k < chirp.size() && i + k < count; ++k) x[i + k] += h[i] * chirp[k];
    }
    std::mt19937 rng(seed);
    std::normal_distribution<double> gauss(0.0, noise);
    for (float& v : x) v += static_cast<float>(gauss(rng));
    return x;
  };
  const double delay = static_cast<double>(lead) + 300.0, shift = 0.37;
  const std::vector<float> a = heard(delay, 0.0, 1), b = heard(delay + shift, 0.0, 2);
  const double alone = timer.Time(a.data(), nullptr, lead);
  EXPECT_NEAR(timer.Together({{a.data(), 0.0, lead}, {b.data(), shift, lead}}), alone, 2e-6);
  EXPECT_NEAR(timer.Time(b.data(), nullptr, lead) - shift / kRate, alone, 2e-6);
  int one = 0, two = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const double noise = 7.0;  // the direct sound under the floor in most single windows
    const std::vector<float> c = heard(delay, noise, 2 * seed), d = heard(delay + shift, noise, 2 * seed + 1);
    if (std::abs(timer.Time(c.data(), nullptr, lead) - alone) < 2e-5) ++one;
    if (std::abs(timer.Together({{c.data(), 0.0, lead}, {d.data(), shift, lead}}) - alone) < 2e-5) ++two;
  }
  EXPECT_GE(two, one + 5) << "one window found the direct sound in " << one << " of 20, two in " << two;
  EXPECT_THROW(timer.Together({}), std::invalid_argument);
}

// The room receiver times every packet it decodes, on its own clock, and nothing else.
TEST(FirstArrivalTest, TheRoomReceiverTimesEachPacketItDecodes) {
  const std::unique_ptr<ModemProfile> room = MakeProfile(Profile::kRoom, ModemOptions{});
  const std::vector<float> h = HardRoom(300.0, 0.6, 7);
  std::vector<float> clean;
  std::vector<double> starts;
  for (std::uint8_t p = 0; p < 3; ++p) {
    clean.resize(clean.size() + static_cast<std::size_t>((0.5 + 0.1 * p) * kRate) + p, 0.0f);
    starts.push_back(static_cast<double>(clean.size()) / kRate);
    const std::vector<float> packet = room->ModulatePacket({p, 1, 2, 3});
    clean.insert(clean.end(), packet.begin(), packet.end());
  }
  clean.resize(clean.size() + static_cast<std::size_t>(kRate), 0.0f);
  const std::vector<RxEvent> events = RoomReceiverHears(clean, h, 10.0);
  const double edge = LeadingEdge(h, kRate);
  std::size_t packets = 0;
  for (const RxEvent& e : events) {
    if (e.kind != RxEvent::Kind::kPacket) {
      EXPECT_TRUE(std::isnan(e.arrival)) << "noise was timed";
      continue;
    }
    ASSERT_EQ(e.data.size(), 4u);
    ASSERT_LT(e.data[0], 3);
    EXPECT_NEAR(e.arrival, starts[e.data[0]] + edge, 1.5e-5) << "packet " << static_cast<int>(e.data[0]);
    ++packets;
  }
  EXPECT_EQ(packets, 3u);
}

TEST(FirstArrivalTest, SilenceHasNoArrivalAndBadCallsAreRefused) {
  const std::vector<float> chirp = room_phy::Chirp(kRate);
  const std::vector<float> silence(chirp.size() * 2, 0.0f);
  EXPECT_TRUE(std::isnan(FirstArrival(silence.data(), silence.size(), chirp, kRate)));
  // Noise without the chirp in it stands out far less than the chirp in the same noise.
  std::vector<float> noise(chirp.size() * 4);
  std::mt19937 rng(3);
  std::normal_distribution<float> gauss(0.0f, 0.1f);
  for (float& v : noise) v = gauss(rng);
  double without = 0.0, with = 0.0;
  FirstArrival(noise.data(), noise.size(), chirp, kRate, &without);
  for (std::size_t k = 0; k < chirp.size(); ++k) noise[1000 + k] += 0.1f * chirp[k];
  const double arrival = FirstArrival(noise.data(), noise.size(), chirp, kRate, &with);
  EXPECT_LT(without, 6.0);
  EXPECT_GT(with, 30.0);
  EXPECT_NEAR(arrival, 1000.0 / kRate, 2.5e-4);  // the band's rise before the sound
  EXPECT_THROW(FirstArrival(silence.data(), chirp.size() - 1, chirp, kRate), std::invalid_argument);
  EXPECT_THROW(FirstArrival(silence.data(), silence.size(), {}, kRate), std::invalid_argument);
  EXPECT_THROW(FirstArrival(silence.data(), silence.size(), chirp, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace nava_modem
