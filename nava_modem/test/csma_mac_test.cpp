#include "nava_modem/csma_mac.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace nava_modem {
namespace {

constexpr double kSilence = -60.0, kLoud = -10.0;

MacOptions Fixed() {
  MacOptions o;
  o.fixed_threshold_db = -30.0;
  return o;
}

// Ticks until the MAC hands back a packet; -1 if it does not within `limit`.
int TicksUntilSend(CsmaMac& mac, double level, int limit = 100000) {
  for (int k = 1; k <= limit; ++k) {
    if (mac.Tick(level)) return k;
  }
  return -1;
}

TEST(CsmaMac, CalibratesTheThresholdFromSilence) {
  MacOptions o;
  o.calibration_time = 1.0;
  o.threshold_margin_db = 6.0;
  CsmaMac mac(o, 1);
  EXPECT_EQ(mac.state(), MacState::kCalibrating);
  const int ticks = static_cast<int>(1.0 / mac.tick_seconds());
  for (int k = 0; k < ticks - 1; ++k) mac.Tick(k == 100 ? -40.0 : kSilence);
  EXPECT_EQ(mac.state(), MacState::kCalibrating);
  mac.Tick(kSilence);
  EXPECT_EQ(mac.state(), MacState::kWaiting);
  EXPECT_DOUBLE_EQ(mac.threshold_db(), -34.0);
}

TEST(CsmaMac, FixedThresholdSkipsCalibration) {
  CsmaMac mac(Fixed(), 1);
  EXPECT_EQ(mac.state(), MacState::kWaiting);
  EXPECT_DOUBLE_EQ(mac.threshold_db(), -30.0);
}

TEST(CsmaMac, BacksOffOnAFreeMediumThenSendsForOnePacketTimeThenGoesDeaf) {
  MacOptions o = Fixed();
  CsmaMac mac(o, 7);
  EXPECT_DOUBLE_EQ(mac.tick_seconds(), 1.0 / 4800.0);
  EXPECT_EQ(mac.packet_ticks(), 1760);  // 110 bits: 367 ms at 300 bps
  ASSERT_TRUE(mac.Enqueue({1, 2, 3, 4}));
  const int wait = TicksUntilSend(mac, kSilence);
  EXPECT_GE(wait, static_cast<int>(o.backoff_min_bits * 16));
  EXPECT_LE(wait, static_cast<int>(o.backoff_max_bits * 16));
  EXPECT_EQ(mac.state(), MacState::kSending);
  EXPECT_EQ(mac.sent(), 1u);
  for (int k = 0; k < mac.packet_ticks() - 1; ++k) mac.Tick(kLoud);  // its own sound
  EXPECT_EQ(mac.state(), MacState::kSending);
  mac.Tick(kLoud);
  EXPECT_EQ(mac.state(), MacState::kDeaf);
  // Deaf: the echo is ignored for deaf_time, then it listens again.
  const int deaf = static_cast<int>(o.deaf_time / mac.tick_seconds());
  for (int k = 0; k < deaf - 1; ++k) mac.Tick(kLoud);
  EXPECT_EQ(mac.state(), MacState::kDeaf);
  EXPECT_EQ(mac.receptions(), 0u);
  mac.Tick(kLoud);
  EXPECT_EQ(mac.state(), MacState::kWaiting);
  mac.Tick(kLoud);
  EXPECT_EQ(mac.state(), MacState::kReceiving);
}

TEST(CsmaMac, CarrierDefersSendingUntilTheMediumIsFree) {
  CsmaMac mac(Fixed(), 3);
  mac.Enqueue({9, 9, 9, 9});
  mac.Tick(kLoud);
  EXPECT_EQ(mac.state(), MacState::kReceiving);
  EXPECT_TRUE(mac.carrier());
  for (int k = 0; k < 5000; ++k) ASSERT_FALSE(mac.Tick(kLoud).has_value());
  // Carrier gone: one bit of release, then a fresh back-off, then the send.
  const int wait = TicksUntilSend(mac, kSilence);
  EXPECT_GE(wait, 16 + static_cast<int>(MacOptions{}.backoff_min_bits * 16));
  EXPECT_EQ(mac.receptions(), 1u);
}

// Each frame holds the air for its own airtime: a 2.5 s frame keeps the MAC sending 2.5 s, and
// the packet queued behind it then goes for a packet's time; a frame without an airtime is refused.
TEST(CsmaMac, EachFrameHoldsTheAirForItsOwnAirtime) {
  CsmaMac mac(Fixed(), 3);
  ASSERT_TRUE(mac.Enqueue(MacFrame{std::vector<std::uint8_t>(64, 1), 2, 2.5}));
  ASSERT_TRUE(mac.Enqueue({1, 2, 3, 4}));
  ASSERT_GT(TicksUntilSend(mac, kSilence), 0);
  const auto sending_for = [&] {
    int ticks = 1;
    while (mac.state() == MacState::kSending) {
      mac.Tick(kLoud);
      ++ticks;
    }
    return ticks - 1;
  };
  EXPECT_EQ(sending_for(), mac.Ticks(2.5));
  ASSERT_GT(TicksUntilSend(mac, kSilence), 0);
  EXPECT_EQ(sending_for(), mac.packet_ticks());
  EXPECT_THROW(mac.Enqueue(MacFrame{{1}, 0, 0.0}), std::invalid_argument);
  EXPECT_THROW(mac.Enqueue(MacFrame{{1}, 0, std::nan("")}), std::invalid_argument);
}

TEST(CsmaMac, QueueOverflowIsCountedNotSilent) {
  MacOptions o = Fixed();
  o.queue_capacity = 2;
  CsmaMac mac(o, 1);
  EXPECT_TRUE(mac.Enqueue({1}));
  EXPECT_TRUE(mac.Enqueue({2}));
  EXPECT_FALSE(mac.Enqueue({3}));
  EXPECT_EQ(mac.dropped(), 1u);
  EXPECT_EQ(mac.queued(), 2u);
  const auto first = [&] {
    for (;;)
      if (auto p = mac.Tick(kSilence)) return *p;
  }();
  EXPECT_EQ(first.data, std::vector<std::uint8_t>({1}));
  EXPECT_EQ(first.rate, 0);
  EXPECT_NEAR(first.airtime, o.packet_bits / o.bit_rate, 1e-12);
}

// A failed device cuts the packet being sent: it goes back to the front of the queue, before
// the packets that waited behind it, even when the queue is full, and the MAC waits the hold
// and a back-off before sending it again.
TEST(CsmaMac, AnInterruptedSendGoesBackToTheFrontAfterAHold) {
  MacOptions o = Fixed();
  o.queue_capacity = 2;
  o.backoff_min_bits = o.backoff_max_bits = 2.0;
  CsmaMac mac(o, 1);
  ASSERT_TRUE(mac.Enqueue({1, 1, 1, 1}));
  ASSERT_TRUE(mac.Enqueue({2, 2, 2, 2}));
  ASSERT_GT(TicksUntilSend(mac, kSilence), 0);
  ASSERT_TRUE(mac.Enqueue({3, 3, 3, 3}));
  EXPECT_FALSE(mac.Enqueue({4, 4, 4, 4}));  // full
  for (int k = 0; k < 100; ++k) mac.Tick(kSilence);
  ASSERT_EQ(mac.state(), MacState::kSending);
  mac.Interrupt({MacFrame{{1, 1, 1, 1}, 0, o.packet_bits / o.bit_rate}}, 0.5);
  EXPECT_EQ(mac.state(), MacState::kWaiting);
  EXPECT_EQ(mac.queued(), 3u);
  EXPECT_EQ(mac.requeued(), 1u);
  const int hold = static_cast<int>(std::lround(0.5 / mac.tick_seconds())) + 32;
  EXPECT_EQ(TicksUntilSend(mac, kSilence), hold);
  std::vector<std::vector<std::uint8_t>> order;
  order.push_back({1, 1, 1, 1});
  for (int n = 0; n < 2; ++n) {
    for (int k = 0; k < mac.packet_ticks() + 2000; ++k) {
      if (auto p = mac.Tick(kSilence)) order.push_back(p->data);
    }
  }
  EXPECT_EQ(order, (std::vector<std::vector<std::uint8_t>>{{1, 1, 1, 1}, {2, 2, 2, 2}, {3, 3, 3, 3}}));
  EXPECT_EQ(mac.sent(), 4u);  // the first one twice
}

// A calibration under way is not cut short by a failure.
TEST(CsmaMac, AnInterruptedCalibrationGoesOn) {
  MacOptions o;
  o.calibration_time = 1.0;
  CsmaMac mac(o, 1);
  for (int k = 0; k < 100; ++k) mac.Tick(kSilence);
  mac.Interrupt({}, 0.5);
  EXPECT_EQ(mac.state(), MacState::kCalibrating);
}

TEST(CsmaMac, RandomBackOffSpreadsRobotsWaitingForTheSameSender) {
  // Ten robots hear the same carrier end; their sends must not all start together.
  std::vector<int> starts;
  for (std::uint32_t seed = 0; seed < 10; ++seed) {
    CsmaMac mac(Fixed(), seed);
    mac.Enqueue({1, 2, 3, 4});
    for (int k = 0; k < 100; ++k) mac.Tick(kLoud);
    starts.push_back(TicksUntilSend(mac, kSilence));
  }
  std::sort(starts.begin(), starts.end());
  EXPECT_GT(starts.back() - starts.front(), 16 * 5) << "back-offs too alike";
  // And the same seed gives the same back-off.
  CsmaMac a(Fixed(), 42), b(Fixed(), 42);
  a.Enqueue({1});
  b.Enqueue({1});
  EXPECT_EQ(TicksUntilSend(a, kSilence), TicksUntilSend(b, kSilence));
}

// The thesis calibrates once; a robot that then drives into a louder room would hear its fan
// as a carrier for ever and never send. The threshold follows the room within the window.
TEST(CsmaMac, TheThresholdFollowsTheFloorIntoALouderRoomAndBack) {
  MacOptions o;
  o.calibration_time = 1.0;
  CsmaMac mac(o, 3);
  const int second = static_cast<int>(std::lround(1.0 / mac.tick_seconds()));
  for (int k = 0; k < 3 * second; ++k) mac.Tick(kSilence);
  EXPECT_DOUBLE_EQ(mac.threshold_db(), kSilence + o.threshold_margin_db);
  // A fan 20 dB louder: a carrier at first...
  ASSERT_TRUE(mac.Enqueue({1, 2, 3, 4}));
  const double fan = kSilence + 20.0;
  int ticks = 0;
  for (; ticks < 9 * second; ++ticks) {
    ASSERT_FALSE(mac.Tick(fan)) << "sent over what it still took for a carrier";
  }
  EXPECT_EQ(mac.state(), MacState::kReceiving);
  // ...until the whole window has heard it; then the fan is the floor and the packet goes.
  EXPECT_GE(TicksUntilSend(mac, fan, 3 * second), 0);
  EXPECT_DOUBLE_EQ(mac.threshold_db(), fan + o.threshold_margin_db);
  // Back in the quiet room the threshold comes down with the first wholly quiet block (the
  // one the packet went in still heard the fan before it).
  for (int k = 0; k < 3 * second; ++k) mac.Tick(kSilence);
  EXPECT_DOUBLE_EQ(mac.threshold_db(), kSilence + o.threshold_margin_db);
}

// Packets (or a slammed door) that leave a quiet block in the window do not move the floor;
// the robot's own sound never does.
TEST(CsmaMac, PassingSoundAndItsOwnPacketsLeaveTheFloorAlone) {
  MacOptions o;
  o.calibration_time = 1.0;
  CsmaMac mac(o, 5);
  const int second = static_cast<int>(std::lround(1.0 / mac.tick_seconds()));
  for (int k = 0; k < second; ++k) mac.Tick(kSilence);
  const double calibrated = mac.threshold_db();
  for (int s = 0; s < 30; ++s) {
    // Every second but every fifth holds a loud packet of someone else.
    for (int k = 0; k < second; ++k) mac.Tick(s % 5 != 0 && k < mac.packet_ticks() ? kLoud : kSilence);
    EXPECT_DOUBLE_EQ(mac.threshold_db(), calibrated) << "second " << s;
  }
  // Its own sending, loud in its own microphone, for much longer than the window.
  for (int s = 0; s < 15; ++s) {
    ASSERT_TRUE(mac.Enqueue({1}));
    for (int k = 0; k < second * 2; ++k) {
      const bool own = mac.state() == MacState::kSending || mac.state() == MacState::kDeaf;
      mac.Tick(own ? kLoud : kSilence);
    }
  }
  EXPECT_DOUBLE_EQ(mac.threshold_db(), calibrated);
}

// Skipping idle ticks at a steady level (the simulated channel does) ends where ticking does.
TEST(CsmaMac, SkippingIdleTicksFollowsTheFloorAsTickingDoes) {
  MacOptions o;
  o.calibration_time = 1.0;
  CsmaMac ticked(o, 9), skipped(o, 9);
  const int second = static_cast<int>(std::lround(1.0 / ticked.tick_seconds()));
  for (int k = 0; k < second; ++k) {
    ticked.Tick(kSilence + 10.0);
    skipped.Tick(kSilence + 10.0);
  }
  for (int k = 0; k < 12 * second + 77; ++k) ticked.Tick(kSilence);
  skipped.SkipIdle(12 * second + 77, kSilence);
  EXPECT_EQ(ticked.ticks(), skipped.ticks());
  EXPECT_DOUBLE_EQ(ticked.threshold_db(), kSilence + o.threshold_margin_db);
  EXPECT_DOUBLE_EQ(skipped.threshold_db(), ticked.threshold_db());
}

TEST(CsmaMac, TheThesisCalibrationOnceWhenTheWindowIsZero) {
  MacOptions o;
  o.calibration_time = 1.0;
  o.floor_window = 0.0;
  CsmaMac mac(o, 3);
  const int second = static_cast<int>(std::lround(1.0 / mac.tick_seconds()));
  for (int k = 0; k < second; ++k) mac.Tick(kSilence);
  for (int k = 0; k < 20 * second; ++k) mac.Tick(kSilence + 20.0);
  EXPECT_DOUBLE_EQ(mac.threshold_db(), kSilence + o.threshold_margin_db);
  EXPECT_EQ(mac.state(), MacState::kReceiving);
}

TEST(NoiseFloor, TheQuietestOfTheLastBlocksLoudestLevels) {
  NoiseFloor floor(4, 3);
  EXPECT_FALSE(floor.floor_db());
  EXPECT_FALSE(floor.Hear(-50.0, 3));
  EXPECT_EQ(floor.TicksToBlockEnd(), 1u);
  EXPECT_TRUE(floor.Hear(-20.0));  // block 1: loudest -20
  EXPECT_DOUBLE_EQ(*floor.floor_db(), -20.0);
  EXPECT_TRUE(floor.Hear(-40.0, 8));  // blocks 2 and 3: -40
  EXPECT_DOUBLE_EQ(*floor.floor_db(), -40.0);
  EXPECT_TRUE(floor.Hear(-30.0, 12));  // three blocks at -30 push the -40s out
  EXPECT_DOUBLE_EQ(*floor.floor_db(), -30.0);
  EXPECT_THROW(NoiseFloor(0, 3), std::invalid_argument);
  EXPECT_THROW(NoiseFloor(4, 0), std::invalid_argument);
}

TEST(CsmaMac, ImpossibleOptionsAreRejected) {
  MacOptions o;
  o.deaf_time = 0.5;  // longer than a 367 ms packet
  EXPECT_THROW(ValidateMacOptions(o), std::invalid_argument);
  o = {};
  o.bit_rate = 0.0;
  EXPECT_THROW(ValidateMacOptions(o), std::invalid_argument);
  o = {};
  o.backoff_max_bits = 1.0;  // below the minimum
  EXPECT_THROW(ValidateMacOptions(o), std::invalid_argument);
  o = {};
  o.queue_capacity = 0;
  EXPECT_THROW(CsmaMac(o, 1), std::invalid_argument);
  o = {};
  o.floor_window = 0.5;  // shorter than a block
  EXPECT_THROW(ValidateMacOptions(o), std::invalid_argument);
  o = {};
  o.floor_block = 0.0;
  EXPECT_THROW(ValidateMacOptions(o), std::invalid_argument);
}

}  // namespace
}  // namespace nava_modem
