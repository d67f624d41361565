// The link across device failures (failing_device.h): every packet plays whole exactly once
// wherever the device fails, reopens follow the back-off schedule, and what was heard before
// a failure is still reported.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <gtest/gtest.h>

#include "failing_device.h"
#include "nava_modem/fsk_receiver.h"
#include "nava_modem/nava_link.h"
#include "nava_modem/room_channel.h"

namespace nava_modem {
namespace {

using test_doubles::FailingDevice;
using test_doubles::ManualClock;

constexpr double kRate = 16000.0;

LinkOptions Sender() {
  LinkOptions o;
  o.modem.sample_rate = kRate;
  o.mac.fixed_threshold_db = -40.0;
  o.mac.backoff_min_bits = o.mac.backoff_max_bits = 2.0;
  return o;
}

std::vector<std::uint8_t> Numbered(int k) { return {0x40, static_cast<std::uint8_t>(k), 0x55, 0xAA}; }

std::size_t Samples(double seconds) { return static_cast<std::size_t>(std::lround(seconds * kRate)); }

// Where `burst` appears whole in `air`, sample for sample.
std::vector<std::size_t> WholeCopies(const std::vector<float>& air, const std::vector<float>& burst) {
  std::vector<std::size_t> at;
  for (std::size_t k = 0; k + burst.size() <= air.size(); ++k) {
    if (std::equal(burst.begin(), burst.end(), air.begin() + static_cast<std::ptrdiff_t>(k))) at.push_back(k);
  }
  return at;
}

struct Played {
  std::vector<float> air;
  std::uint64_t requeued = 0, faults = 0, reopens = 0;
};

// Sends packets 1 to 3 at once through a device 0.1 s deep that fails at `fail_at` s of
// capture (none if negative).
Played SendThree(double fail_at) {
  const LinkOptions o = Sender();
  ManualClock clock;
  FailingDevice::Options d;
  d.rate = kRate;
  d.delay = Samples(0.1);
  d.input.assign(Samples(5.0), 0.0f);
  if (fail_at >= 0.0) d.fail_at = {Samples(fail_at)};
  FailingDevice device(d, clock);
  NavaLink link(o, device, clock);
  for (int k = 1; k <= 3; ++k) EXPECT_TRUE(link.Send(Numbered(k)));
  std::vector<RxEvent> events;
  while (link.Tick(events)) {
  }
  return {device.air(), link.packets_requeued(), link.device_faults(), link.reopens()};
}

// Wherever the device fails, before, inside or after a packet's sound or while it waits in the
// device's buffer, each packet plays whole exactly once, and a packet is sent again exactly
// when the failure came between its first sample's write and its last sample's playing.
// Decoded as a listener would, the air holds each packet once, in order, unless the failure
// cut a packet in its last 45 ms: the receiver can still decode such a packet (it reads the
// missing bits from its filters' ringing and repairs the rest by CRC), and then hears it again
// when it is sent again (a limit of the link: it goes by what was played).
TEST(DeviceFault, EveryPacketPlaysWholeExactlyOnceWhereverTheDeviceFails) {
  const LinkOptions o = Sender();
  const auto profile = MakeProfile(o.profile, o.modem);
  std::vector<std::vector<float>> bursts;
  for (int k = 1; k <= 3; ++k) bursts.push_back(profile->ModulatePacket(Numbered(k)));
  // Without a failure: where each packet is on the air, and so when it was in flight (written
  // 0.1 s before it plays).
  const Played clean = SendThree(-1.0);
  std::vector<std::pair<double, double>> on_air;
  for (const auto& burst : bursts) {
    const std::vector<std::size_t> at = WholeCopies(clean.air, burst);
    ASSERT_EQ(at.size(), 1u);
    on_air.push_back({at[0] / kRate, (at[0] + burst.size()) / kRate});
  }
  int requeued_runs = 0, decoded_runs = 0;
  for (double fail_at = 0.02; fail_at < 1.8; fail_at += 0.023) {
    SCOPED_TRACE("failure at " + std::to_string(fail_at) + " s");
    const Played run = SendThree(fail_at);
    EXPECT_EQ(run.faults, 1u);
    EXPECT_EQ(run.reopens, 1u);
    for (std::size_t k = 0; k < bursts.size(); ++k) {
      EXPECT_EQ(WholeCopies(run.air, bursts[k]).size(), 1u) << "packet " << k + 1;
    }
    // Sent again when, and only when, it was in flight (with margins of a block: the link
    // writes and reads every 5 ms).
    int inside = 0, near = 0;
    bool end_cut = false;
    for (const auto& [from, to] : on_air) {
      inside += fail_at > from - 0.1 + 0.011 && fail_at < to - 0.011;
      near += fail_at > from - 0.1 - 0.011 && fail_at < to + 0.011;
      end_cut = end_cut || (fail_at > to - 0.045 && fail_at < to + 0.011);
    }
    if (inside > 0) {
      EXPECT_GE(run.requeued, 1u);
    }
    if (near == 0) {
      EXPECT_EQ(run.requeued, 0u);
    }
    requeued_runs += run.requeued > 0;
    if (end_cut) continue;
    FskReceiver rx(o.modem, {});
    std::vector<RxEvent> heard;
    rx.Process(run.air.data(), run.air.size(), heard);
    rx.Flush(heard);
    std::vector<int> numbers;
    for (const RxEvent& e : heard) {
      if (e.kind == RxEvent::Kind::kPacket) numbers.push_back(e.data[1]);
    }
    EXPECT_EQ(numbers, (std::vector<int>{1, 2, 3}));
    ++decoded_runs;
  }
  EXPECT_GT(requeued_runs, 30);  // the sweep did hit packets in flight
  EXPECT_GT(decoded_runs, 60);
}

// Reopen tries come 0.1, 0.3, 0.7, 1.5, 3.1 s after the failure (the wait doubling from 0.1 s),
// then every 2 s (the cap); a tick never waits more than 50 ms; the link then sends on.
TEST(DeviceFault, ReopensOnTheBackOffScheduleAndSendsOn) {
  LinkOptions o = Sender();
  o.reopen.first_wait = 0.1;
  o.reopen.max_wait = 2.0;
  ManualClock clock;
  FailingDevice::Options d;
  d.rate = kRate;
  d.input.assign(Samples(4.0), 0.0f);
  d.fail_at = {Samples(0.2), Samples(2.5)};
  d.refusals = 7;
  FailingDevice device(d, clock);
  NavaLink link(o, device, clock);
  for (int k = 1; k <= 3; ++k) ASSERT_TRUE(link.Send(Numbered(k)));
  std::vector<RxEvent> events;
  bool seen_down = false;
  const double start = clock.Now();
  while (link.Tick(events)) seen_down = seen_down || link.device_down();
  EXPECT_TRUE(seen_down);
  EXPECT_FALSE(link.device_down());
  EXPECT_EQ(link.device_faults(), 2u);
  EXPECT_EQ(link.reopens(), 2u);
  EXPECT_EQ(link.failed_reopens(), 7);
  EXPECT_EQ(link.device_error(), "no such card yet");  // the last failed try's
  const std::vector<double> after = {0.1, 0.3, 0.7, 1.5, 3.1, 5.1, 7.1, 9.1};
  ASSERT_EQ(device.tries().size(), 2 * after.size());
  for (std::size_t k = 0; k < after.size(); ++k) {
    EXPECT_NEAR(device.tries()[k] - start, after[k], 1e-6) << "try " << k;
    EXPECT_NEAR(device.tries()[after.size() + k] - device.tries()[after.size() - 1], after[k], 1e-6) << "try " << k;
  }
  EXPECT_LE(clock.longest_sleep(), 0.05 + 1e-12);
  EXPECT_EQ(link.packets_sent(), 3u + link.packets_requeued());
  for (int k = 1; k <= 3; ++k) EXPECT_EQ(WholeCopies(device.air(), MakeProfile(o.profile, o.modem)->ModulatePacket(Numbered(k))).size(), 1u);
}

// What the link had heard when its device failed is decoded to its end: a packet that had just
// ended is reported once (the room receiver only reports a third of a second late), and one
// heard after the reopen is. A packet cut halfway is not reported by `nava`; `room` reports it,
// once and right: its first chirp was heard, the data search (DecodeByData) places the symbols
// after it, and its rate-1/3 code carries the payload in the half it heard.
// What a link hears: packets 7, 8 and 9 with 0.5 s of silence before each, 4 s after, and two
// points to fail at: 10 ms after 7 ends, and halfway through 8.
struct ThreeHeard {
  std::vector<float> input;
  std::size_t fail_1 = 0, fail_2 = 0;
};

ThreeHeard ThreePackets(const ModemProfile& modem) {
  ThreeHeard h;
  const std::vector<float> a = modem.ModulatePacket(Numbered(7)), b = modem.ModulatePacket(Numbered(8)),
                           c = modem.ModulatePacket(Numbered(9));
  h.input.assign(Samples(0.5), 0.0f);
  h.input.insert(h.input.end(), a.begin(), a.end());
  h.fail_1 = h.input.size() + Samples(0.01);
  h.input.resize(h.input.size() + Samples(0.5), 0.0f);
  h.fail_2 = h.input.size() + b.size() / 2;
  h.input.insert(h.input.end(), b.begin(), b.end());
  h.input.resize(h.input.size() + Samples(0.5), 0.0f);
  h.input.insert(h.input.end(), c.begin(), c.end());
  h.input.resize(h.input.size() + Samples(4.0), 0.0f);
  return h;
}

struct Heard {
  std::map<int, int> packets;  // by number, how often
  std::uint64_t faults = 0;
};

// A link capturing `input` through a device that fails at `fail_at`: what it reports.
Heard HearThrough(const LinkOptions& o, const std::vector<float>& input, const std::vector<std::size_t>& fail_at) {
  ManualClock clock;
  FailingDevice::Options d;
  d.rate = kRate;
  d.input = input;
  d.fail_at = fail_at;
  FailingDevice device(d, clock);
  NavaLink link(o, device, clock);
  std::vector<RxEvent> events;
  Heard heard;
  while (link.Tick(events)) {
    for (const RxEvent& e : events) {
      if (e.kind == RxEvent::Kind::kPacket) ++heard.packets[e.data[1]];
      EXPECT_LE(e.end, link.time() + 1e-9);
    }
    events.clear();
  }
  heard.faults = link.device_faults();
  return heard;
}

TEST(DeviceFault, WhatWasHeardBeforeAFailureIsStillReported) {
  for (const Profile profile : {Profile::kNava, Profile::kRoom}) {
    SCOPED_TRACE(ProfileName(profile));
    LinkOptions o = Sender();
    o.profile = profile;
    const ThreeHeard h = ThreePackets(*MakeProfile(profile, o.modem));
    const Heard heard = HearThrough(o, h.input, {h.fail_1, h.fail_2});
    EXPECT_EQ(heard.faults, 2u);
    if (profile == Profile::kNava) {
      EXPECT_EQ(heard.packets, (std::map<int, int>{{7, 1}, {9, 1}}));
    } else {
      EXPECT_EQ(heard.packets, (std::map<int, int>{{7, 1}, {8, 1}, {9, 1}}));
    }
  }
}

// The same for the room profile in a room where the reverberation is louder than the direct
// sound (DRR -5 dB, RT60 0.5 s), with pink noise, a motor whine, a speaker whose highs are 6 dB
// weaker and the sender's clock 0.2 % fast: the failure keeps what was heard, loses only the
// packet it cut, and the link hears the rest. Without failures it hears all three (so a packet
// missing is the failure's doing, not the room's).
TEST(DeviceFault, WhatWasHeardBeforeAFailureIsStillReportedInAReverberantRoom) {
  LinkOptions o = Sender();
  o.profile = Profile::kRoom;
  const ThreeHeard h = ThreePackets(*MakeProfile(Profile::kRoom, o.modem));
  RoomOptions room;
  room.rt60 = 0.5;
  room.drr_db = -5.0;
  room.tilt_db = -6.0;
  room.clock_offset = 0.002;
  room.noise = RoomOptions::Noise::kPink;
  room.snr_db = 15.0;
  room.whine_hz = 1800.0;
  room.whine_sir_db = 10.0;
  room.seed = 3;
  const std::vector<float> heard_in_room = RenderRoom(h.input, kRate, room);
  // The clock offset shortens the sound by 1 / (1 + offset): the failure points move with it.
  const auto shifted = [&](std::size_t at) {
    return static_cast<std::size_t>(std::lround(static_cast<double>(at) / (1.0 + room.clock_offset)));
  };
  const Heard whole = HearThrough(o, heard_in_room, {});
  EXPECT_EQ(whole.packets, (std::map<int, int>{{7, 1}, {8, 1}, {9, 1}}));
  const Heard failing = HearThrough(o, heard_in_room, {shifted(h.fail_1), shifted(h.fail_2)});
  EXPECT_EQ(failing.faults, 2u);
  EXPECT_EQ(failing.packets, (std::map<int, int>{{7, 1}, {9, 1}}));
}

// The link's process stalls for 0.5 s while it is deaf after its first packet; its device
// keeps the capture, and the link falls 0.5 s behind. It catches up by not playing silence,
// hearing everything it captured meanwhile, including another robot's packet X near the end of
// the backlog; and it starts no send while behind, whose carrier sense would be stale: its
// second packet goes out after X (the air free again), not into it.
TEST(DeviceFault, ALinkBehindItsCaptureCatchesUpAndSendsNothingMeanwhile) {
  LinkOptions o = Sender();
  // A back-off longer than the receiver takes to decode X after its end (a send mutes the
  // receiver, which drops a packet it has not finished decoding).
  o.mac.backoff_min_bits = o.mac.backoff_max_bits = 10.0;
  const auto modem = MakeProfile(o.profile, o.modem);
  ManualClock clock;
  FailingDevice::Options d;
  d.rate = kRate;
  d.delay = Samples(0.1);
  d.input.assign(Samples(5.0), 0.0f);
  const std::vector<float> x = modem->ModulatePacket({0x77, 0x77, 0x77, 0x77});
  const std::size_t x_at = Samples(0.9);
  std::copy(x.begin(), x.end(), d.input.begin() + static_cast<std::ptrdiff_t>(x_at));
  d.stall_at = Samples(0.45);
  d.stall = Samples(0.5);
  FailingDevice device(d, clock);
  NavaLink link(o, device, clock);
  for (int k = 1; k <= 3; ++k) ASSERT_TRUE(link.Send(Numbered(k)));
  std::vector<RxEvent> events;
  while (link.Tick(events)) {
  }
  EXPECT_EQ(link.catch_ups(), 1u);
  int heard_x = 0;
  for (const RxEvent& e : events) heard_x += e.kind == RxEvent::Kind::kPacket && e.data[0] == 0x77;
  EXPECT_EQ(heard_x, 1) << "the backlog was not heard whole";
  // After the stall the air runs in step with capture again: X ended at capture (and air)
  // time (x_at + |x|) / rate.
  for (int k = 1; k <= 3; ++k) {
    const std::vector<std::size_t> at = WholeCopies(device.air(), modem->ModulatePacket(Numbered(k)));
    ASSERT_EQ(at.size(), 1u) << "packet " << k;
    if (k == 2) {
      EXPECT_GT(at[0], x_at + x.size()) << "packet 2 went out into X";
    }
  }
}

// A link that cannot catch up (its backlog never shrinks: a machine too slow for real time)
// holds its sends for 2 s of audio only, then sends on stale carrier sense rather than never.
TEST(DeviceFault, ALinkThatCannotCatchUpStillSends) {
  const LinkOptions o = Sender();
  ManualClock clock;
  FailingDevice::Options d;
  d.rate = kRate;
  d.input.assign(Samples(4.0), 0.0f);
  d.stall_at = 0;
  d.stall = Samples(10.0);
  FailingDevice device(d, clock);
  NavaLink link(o, device, clock);
  ASSERT_TRUE(link.Send(Numbered(1)));
  std::vector<RxEvent> events;
  double sent_at = -1.0;
  while (link.Tick(events)) {
    if (sent_at < 0.0 && link.packets_sent() > 0) sent_at = link.time();
  }
  EXPECT_EQ(link.catch_ups(), 1u);
  EXPECT_NEAR(sent_at, 2.0, 0.05);
}

TEST(DeviceFault, ImpossibleReopenOptionsAreRejected) {
  for (const auto& [first, max, settle] : std::vector<std::tuple<double, double, double>>{
           {0.0, 2.0, 0.5}, {-1.0, 2.0, 0.5}, {0.5, 0.2, 0.5}, {0.1, 1e9, 0.5}, {0.1, 2.0, -1.0}, {NAN, 2.0, 0.5}}) {
    ReopenOptions r;
    r.first_wait = first;
    r.max_wait = max;
    r.settle_time = settle;
    EXPECT_THROW(ValidateReopenOptions(r), std::invalid_argument) << first << " " << max << " " << settle;
    LinkOptions o = Sender();
    o.reopen = r;
    ManualClock clock;
    FailingDevice::Options d;
    d.rate = kRate;
    FailingDevice device(d, clock);
    EXPECT_THROW(NavaLink(o, device, clock), std::invalid_argument);
  }
  EXPECT_NO_THROW(ValidateReopenOptions(ReopenOptions{}));
}

}  // namespace
}  // namespace nava_modem
