#include "audio_propagation/audio_channel.h"

#include <cmath>

#include <gtest/gtest.h>

#include "run_channel.h"

#include "nava_modem/modem_profile.h"

namespace audio_propagation {
namespace {

using world_sim::Microphone;

// An open strip 45 x 5 m (test::Loud: heard up to 31.6 m).
using test::Loud;

struct Team {
  PropagationModel model{grid::OccupancyMap(90, 10, 0.5), Loud()};
  std::unique_ptr<AudioChannel> channel;

  Team(const std::vector<double>& xs, ChannelOptions options = {}) {
    channel = std::make_unique<AudioChannel>(model, std::vector<Microphone>(xs.size(), Microphone::kOmni), options);
    for (std::size_t k = 0; k < xs.size(); ++k) channel->SetPose(k, {xs[k], 2.5, 0.0});
  }

  // Runs for `seconds` and gathers everything.
  AudioChannel::Events Run(double seconds) { return test::RunFor(*channel, seconds); }
};

TEST(AudioChannel, APacketArrivesAfterItsDurationAndTravelTimeWithItsLevel) {
  Team team({2.0, 12.0});
  ASSERT_TRUE(team.channel->Send(0, {1, 2, 3, 4}));
  const auto events = team.Run(1.0);
  ASSERT_EQ(events.started.size(), 1u);
  const Transmission& tx = events.started[0];
  EXPECT_NEAR(tx.duration, 110.0 / 300.0, 1e-9);
  ASSERT_EQ(events.received.size(), 1u);  // the sender does not hear itself
  const Reception& rx = events.received[0];
  EXPECT_EQ(rx.receiver, 1u);
  EXPECT_EQ(rx.kind, Reception::Kind::kPacket);
  EXPECT_EQ(rx.data, std::vector<std::uint8_t>({1, 2, 3, 4}));
  EXPECT_NEAR(rx.path_length, 10.0, 1e-9);
  EXPECT_NEAR(rx.level_db, 60.0 - 20.0, 1e-9);
  EXPECT_NEAR(rx.time - tx.start, tx.duration + 10.0 / 343.0, 2.0 * team.channel->tick_seconds());
  EXPECT_NEAR(rx.direction, M_PI, 1e-9);  // from behind: the sender is at smaller x
}

// The simulated link runs the robots' modem profile: a room packet sounds its 1.92 s, raising
// the listener's carrier all that time, and a packet sent 1 s into it collides.
TEST(AudioChannel, APacketLastsItsProfilesAirtime) {
  ChannelOptions options;
  nava_modem::UseProfileTiming(nava_modem::Profile::kRoom, {}, options.mac);
  options.mac.backoff_min_bits = options.mac.backoff_max_bits = 2.0;
  // Robots 0 and 2 are 40 m apart, out of each other's hearing: robot 0's carrier cannot keep
  // robot 2 from sending into robot 1's reception.
  Team team({2.0, 22.0, 42.0}, options);
  ASSERT_TRUE(team.channel->Send(0, {1, 2, 3, 4}));
  auto events = team.Run(1.0);
  ASSERT_EQ(events.started.size(), 1u);
  const double airtime = nava_modem::ProfileAirtime(nava_modem::Profile::kRoom);
  EXPECT_NEAR(events.started[0].duration, airtime, 1e-9);
  EXPECT_TRUE(team.channel->Carrier(1)) << "still hearing the packet after 1 s";
  events = team.Run(airtime);
  ASSERT_EQ(events.received.size(), 1u);
  EXPECT_EQ(events.received[0].kind, Reception::Kind::kPacket);
  EXPECT_NEAR(events.received[0].time, airtime + 20.0 / 343.0, 0.1);
  EXPECT_FALSE(team.channel->Carrier(1));

  ASSERT_TRUE(team.channel->Send(0, {1, 2, 3, 4}));
  team.Run(1.0);
  ASSERT_TRUE(team.channel->Send(2, {5, 6, 7, 8}));
  events = team.Run(2.0 * airtime);
  int noise_at_1 = 0;
  for (const Reception& r : events.received) noise_at_1 += r.receiver == 1 && r.kind == Reception::Kind::kNoise;
  EXPECT_EQ(noise_at_1, 2) << "both overlapping packets lost at the robot between the senders";
}

// A frame holds the air for its own airtime, by its length and rate: a 64-byte room frame at
// rate 1 for its 4.7 s, arriving whole with its rate; and a packet sent 3 s into it, where a
// 4-byte packet would long have ended, collides with it at the robot between.
TEST(AudioChannel, AFrameLastsItsOwnAirtimeByLengthAndRate) {
  ChannelOptions options;
  const nava_modem::Profile room = nava_modem::Profile::kRoom;
  nava_modem::UseProfileTiming(room, {}, options.mac);
  options.mac.backoff_min_bits = options.mac.backoff_max_bits = 2.0;
  Team team({2.0, 22.0, 42.0}, options);
  std::vector<std::uint8_t> data(64);
  for (std::size_t k = 0; k < data.size(); ++k) data[k] = static_cast<std::uint8_t>(7 * k);
  const double airtime = nava_modem::FrameAirtime(room, {}, data.size(), 1);
  ASSERT_GT(airtime, 2.0 * nava_modem::ProfileAirtime(room));
  ASSERT_TRUE(team.channel->Send(0, nava_modem::MacFrame{data, 1, airtime}));
  auto events = team.Run(airtime - 0.5);
  ASSERT_EQ(events.started.size(), 1u);
  EXPECT_NEAR(events.started[0].duration, airtime, team.channel->tick_seconds());
  EXPECT_EQ(events.started[0].rate, 1);
  EXPECT_TRUE(events.received.empty());
  EXPECT_TRUE(team.channel->Carrier(1)) << "the frame still sounds half a second before its end";
  events = team.Run(1.0);
  ASSERT_EQ(events.received.size(), 1u);
  EXPECT_EQ(events.received[0].kind, Reception::Kind::kPacket);
  EXPECT_EQ(events.received[0].data, data);
  EXPECT_EQ(events.received[0].rate, 1);

  ASSERT_TRUE(team.channel->Send(0, nava_modem::MacFrame{data, 1, airtime}));
  team.Run(3.0);
  ASSERT_TRUE(team.channel->Send(2, {5, 6, 7, 8}));
  events = team.Run(airtime + 3.0);
  int noise_at_1 = 0;
  for (const Reception& r : events.received) noise_at_1 += r.receiver == 1 && r.kind == Reception::Kind::kNoise;
  EXPECT_EQ(noise_at_1, 2) << "the packet sent into the frame's fourth second lost both at the robot between";
}

// A frame with no airtime is a caller's mistake, named.
TEST(AudioChannel, AFrameWithoutAirtimeIsRefused) {
  Team team({2.0, 12.0});
  EXPECT_THROW(team.channel->Send(0, nava_modem::MacFrame{{1, 2, 3, 4}, 0, 0.0}), std::invalid_argument);
  EXPECT_THROW(team.channel->SendAt(0, nava_modem::MacFrame{{1, 2, 3, 4}, 0, -1.0}, 0.0), std::invalid_argument);
}

TEST(AudioChannel, CarrierRisesWhileAPacketIsHeardAndFallsAfter) {
  Team team({2.0, 12.0});
  team.channel->Send(0, {1, 2, 3, 4});
  bool raised = false;
  double raised_at = -1.0;
  while (team.channel->time() < 0.3) {
    team.channel->AdvanceTo(team.channel->time() + 0.001);
    if (team.channel->Carrier(1) && !raised) {
      raised = true;
      raised_at = team.channel->time();
    }
    EXPECT_FALSE(team.channel->Carrier(0));  // its own sound is not a carrier
  }
  ASSERT_TRUE(raised);
  EXPECT_GT(team.channel->Level(1), 30.0);
  team.Run(0.5);
  EXPECT_FALSE(team.channel->Carrier(1));
  EXPECT_EQ(team.channel->Level(1), ChannelOptions{}.noise_floor_db);
  EXPECT_GT(raised_at, 0.0);
}

TEST(AudioChannel, NothingArrivesBeyondHearing) {
  Team team({2.0, 40.0});  // 38 m: below the threshold
  team.channel->Send(0, {5, 5, 5, 5});
  EXPECT_TRUE(team.Run(1.0).received.empty());
}

TEST(AudioChannel, HiddenSendersCollideAtAListenerBetweenThem) {
  // 0 and 2 are 39 m apart and cannot hear each other, so CSMA cannot keep them apart.
  ChannelOptions o;
  o.mac.backoff_min_bits = o.mac.backoff_max_bits = 2.0;  // both start together
  Team team({1.0, 20.0, 40.0}, o);
  team.channel->Send(0, {1, 1, 1, 1});
  team.channel->Send(2, {2, 2, 2, 2});
  const auto events = team.Run(1.0);
  ASSERT_EQ(events.started.size(), 2u);
  int at_middle = 0;
  for (const Reception& r : events.received) {
    if (r.receiver != 1) continue;
    ++at_middle;
    EXPECT_EQ(r.kind, Reception::Kind::kNoise);
    EXPECT_TRUE(r.collision);
    EXPECT_TRUE(r.data.empty());
  }
  EXPECT_EQ(at_middle, 2);
}

TEST(AudioChannel, TheMuchLouderPacketIsCaptured) {
  ChannelOptions o;
  o.mac.backoff_min_bits = o.mac.backoff_max_bits = 2.0;
  o.capture_margin_db = 5.0;
  Team team({1.0, 30.0, 40.0}, o);  // at robot 1: 29 m (30.7 dB) and 10 m (40 dB)
  team.channel->Send(0, {1, 1, 1, 1});
  team.channel->Send(2, {2, 2, 2, 2});
  const auto events = team.Run(1.0);
  int packets = 0, noise = 0;
  for (const Reception& r : events.received) {
    if (r.receiver != 1) continue;
    if (r.kind == Reception::Kind::kPacket) {
      ++packets;
      EXPECT_EQ(r.sender, 2u);
    } else {
      ++noise;
      EXPECT_EQ(r.sender, 0u);
    }
  }
  EXPECT_EQ(packets, 1);
  EXPECT_EQ(noise, 1);
}

TEST(AudioChannel, CarrierSenseKeepsNeighboursApart) {
  // Two robots 1 m apart both want to send at once: the random back-off and the carrier keep
  // their packets apart unless their back-offs end within the 3 ms the sound needs to travel.
  // Robots that cannot hear each other collide in every draw (see HiddenSenders...).
  int clean = 0;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    ChannelOptions o;
    o.seed = seed;
    Team team({2.0, 3.0}, o);
    team.channel->Send(0, {1, 0, 0, 0});
    team.channel->Send(1, {2, 0, 0, 0});
    const auto events = team.Run(2.0);
    int packets = 0;
    for (const Reception& r : events.received) packets += r.kind == Reception::Kind::kPacket;
    clean += packets == 2;
  }
  EXPECT_GE(clean, 16);
}

TEST(AudioChannel, ReusesCachedPathsWhileRobotsStayInTheirCells) {
  ChannelOptions options;
  options.cache_size = 16;
  Team team({2.0, 12.0, 20.0}, options);
  ASSERT_TRUE(team.channel->Send(0, {1, 2, 3, 4}));
  team.Run(1.0);
  EXPECT_EQ(team.channel->cache().size(), 2u);  // robot 0 to robots 1 and 2
  EXPECT_EQ(team.channel->cache().hits(), 0u);
  // A few centimetres on, in the same 0.5 m cells: the paths come from the cache.
  team.channel->SetPose(1, {12.1, 2.5, 0.0});
  ASSERT_TRUE(team.channel->Send(0, {5, 6, 7, 8}));
  const auto events = team.Run(1.0);
  EXPECT_EQ(team.channel->cache().hits(), 2u);
  ASSERT_EQ(events.received.size(), 2u);
  EXPECT_NEAR(events.received[0].path_length, 10.0, 1e-9);  // as computed for the first packet
  // Into another cell: computed again.
  team.channel->SetPose(1, {14.2, 2.5, 0.0});
  ASSERT_TRUE(team.channel->Send(0, {9, 9, 9, 9}));
  const auto moved = team.Run(1.0);
  ASSERT_EQ(moved.received.size(), 2u);
  EXPECT_NEAR(moved.received[0].path_length, 12.2, 1e-9);
  EXPECT_EQ(team.channel->cache().size(), 3u);
}

TEST(AudioChannel, SameSeedSameEvents) {
  auto run = [] {
    ChannelOptions o;
    o.seed = 9;
    o.direction_noise = 0.2;
    Team team({2.0, 8.0, 14.0}, o);
    for (std::size_t k = 0; k < 3; ++k) team.channel->Send(k, {static_cast<std::uint8_t>(k), 0, 0, 0});
    return team.Run(3.0);
  };
  const auto a = run(), b = run();
  ASSERT_EQ(a.received.size(), b.received.size());
  for (std::size_t k = 0; k < a.received.size(); ++k) {
    EXPECT_EQ(a.received[k].time, b.received[k].time);
    EXPECT_EQ(a.received[k].direction, b.received[k].direction);
    EXPECT_EQ(a.received[k].kind, b.received[k].kind);
  }
}

TEST(AudioChannel, SkipsSilenceWithoutLosingTime) {
  Team team({2.0, 12.0});
  team.Run(100.0);  // nothing to say: skipped, but every MAC still counts the ticks
  const double tick = team.channel->tick_seconds();
  EXPECT_NEAR(team.channel->mac(0).ticks() * tick, 100.0, 2.0 * tick);
  EXPECT_NEAR(team.channel->mac(1).ticks() * tick, 100.0, 2.0 * tick);
  team.channel->Send(0, {9, 9, 9, 9});
  const auto events = team.Run(1.0);
  ASSERT_EQ(events.started.size(), 1u);
  // Sent after the MAC's random back-off from now, not from when the silence began.
  const nava_modem::MacOptions mac;
  EXPECT_GE(events.started[0].start, 100.0 + mac.backoff_min_bits / mac.bit_rate - 2.0 * tick);
  EXPECT_LE(events.started[0].start, 100.0 + (mac.backoff_max_bits + 1.0) / mac.bit_rate);
  ASSERT_EQ(events.received.size(), 1u);
  EXPECT_NEAR(events.received[0].time - events.started[0].start, events.started[0].duration + 10.0 / 343.0,
              2.0 * tick);
}

}  // namespace
}  // namespace audio_propagation
