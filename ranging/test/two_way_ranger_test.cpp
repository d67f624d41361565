// Two-way ranging on a scripted team: robots at known places, each with a sound card whose
// clock is offset and runs fast or slow, each speaker a little from its own microphone; packets
// timed by everyone who hears them. The arithmetic, the pairing, and the refusals.
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ranging/two_way_ranger.h"

namespace ranging {
namespace {

constexpr double kC = 343.0;

struct Robot {
  double x = 0.0, y = 0.0;
  double clock_offset = 0.0;  // s: its capture clock at true time 0
  double clock_rate = 0.0;    // its clock runs (1 + this) fast
  double self_delay = 0.0;    // s from its speaker to its own microphone
};

// A team and its packets: Send() makes every robot that hears a packet time it.
class Scene {
 public:
  explicit Scene(std::map<std::string, Robot> robots, double timing_noise = 0.0, unsigned seed = 1)
      : robots_(std::move(robots)), noise_(0.0, timing_noise), rng_(seed) {}
  double Distance(const std::string& a, const std::string& b) const {
    return std::hypot(robots_.at(a).x - robots_.at(b).x, robots_.at(a).y - robots_.at(b).y);
  }
  // `sender`'s packet carrying `id` leaves its speaker at true time t; heard by `listeners`.
  std::vector<Timing> Send(const std::string& sender, std::uint8_t id, double t, const std::vector<std::string>& listeners) {
    std::vector<Timing> out;
    for (const std::string& l : listeners) {
      const Robot& r = robots_.at(l);
      const double heard = t + (l == sender ? robots_.at(sender).self_delay : Distance(sender, l) / kC);
      Timing timing;
      timing.sender = sender;
      timing.listener = l;
      timing.data = {static_cast<std::uint8_t>(sender.back()), id, 0xAB, 0xCD};
      timing.arrival = r.clock_offset + (1.0 + r.clock_rate) * heard + (noise_.stddev() > 0.0 ? noise_(rng_) : 0.0);
      timing.rate_error = l == sender ? 0.0 : (1.0 + robots_.at(sender).clock_rate) / (1.0 + r.clock_rate) - 1.0;
      out.push_back(timing);
    }
    return out;
  }
  // A's clock at true time t.
  double Clock(const std::string& robot, double t) const { return robots_.at(robot).clock_offset + (1.0 + robots_.at(robot).clock_rate) * t; }

 private:
  std::map<std::string, Robot> robots_;
  std::normal_distribution<double> noise_;
  std::mt19937 rng_;
};

void AddAll(TwoWayRanger& ranger, const std::vector<Timing>& timings) {
  for (const Timing& t : timings) ranger.Add(t);
}

std::map<std::string, Robot> Pair(double distance) {
  return {{"a", Robot{0.0, 0.0, 1234.5, 80e-6, 0.0}}, {"b", Robot{distance, 0.0, -50.25, -60e-6, 0.0}}};
}

TEST(TwoWayRangerTest, SkewedClocksAndUnknownLatenciesCancel) {
  for (double d : {0.0, 0.5, 7.3, 15.0, 42.0}) {
    Scene scene(Pair(d));
    TwoWayRanger ranger("a", {"a", "b"}, RangerOptions{});
    ranger.SetOwnRateError(80e-6);
    for (int k = 0; k < 4; ++k) {
      AddAll(ranger, scene.Send("a", static_cast<std::uint8_t>(k), 10.0 + 5.0 * k, {"a", "b"}));
      AddAll(ranger, scene.Send("b", static_cast<std::uint8_t>(k), 12.5 + 5.0 * k, {"b", "a"}));
    }
    const auto r = ranger.RangeTo("b", scene.Clock("a", 30.0));
    ASSERT_TRUE(r) << d;
    EXPECT_NEAR(r->range, d, 1e-4) << d;
    EXPECT_EQ(r->samples, 5) << d;  // one per completed exchange, the latest five
    EXPECT_EQ(ranger.refused().total(), 0u);
  }
}

// The rate correction is what makes it work: the clocks' 140 ppm over 2.5 s is 6 cm. With the
// receivers' measure of it at 0 (nava's bit clock is good to 0.1 % only), the first exchange is
// that far off; once the teammate's packets span 2 s, the rate comes from the timings themselves.
TEST(TwoWayRangerTest, TheRateIsLearntFromTheTimingsThemselves) {
  Scene scene(Pair(3.0));
  TwoWayRanger ranger("a", {"a", "b"}, RangerOptions{});
  ranger.SetOwnRateError(80e-6);
  for (int k = 0; k < 3; ++k) {
    AddAll(ranger, scene.Send("a", static_cast<std::uint8_t>(k), 10.0 + 5.0 * k, {"a", "b"}));
    std::vector<Timing> reply = scene.Send("b", static_cast<std::uint8_t>(k), 12.5 + 5.0 * k, {"b", "a"});
    for (Timing& t : reply) t.rate_error = 0.0;
    AddAll(ranger, reply);
    const auto r = ranger.RangeTo("b", scene.Clock("a", 13.0 + 5.0 * k));
    ASSERT_TRUE(r);
    if (k == 0) {
      EXPECT_GT(std::abs(r->range - 3.0), 0.05) << "one packet of b's tells no rate";
    }
  }
  // Five samples: the first exchange's, and four on the learnt rate.
  const auto r = ranger.RangeTo("b", scene.Clock("a", 30.0));
  EXPECT_EQ(r->samples, 5);
  EXPECT_NEAR(r->range, 3.0, 1e-4);
}

TEST(TwoWayRangerTest, TheSpeakerToMicrophoneDelaysAreTakenOutByTheOffset) {
  std::map<std::string, Robot> robots = Pair(4.0);
  robots["a"].self_delay = 0.0004;
  robots["b"].self_delay = 0.0006;
  Scene scene(robots);
  RangerOptions o;
  o.offset = kC * (0.0004 + 0.0006) / 2.0;
  TwoWayRanger calibrated("a", {"a", "b"}, o), raw("a", {"a", "b"}, RangerOptions{});
  for (int k = 0; k < 3; ++k) {
    for (TwoWayRanger* r : {&calibrated, &raw}) {
      AddAll(*r, scene.Send("a", static_cast<std::uint8_t>(k), 10.0 + 5.0 * k, {"a", "b"}));
      AddAll(*r, scene.Send("b", static_cast<std::uint8_t>(k), 11.0 + 5.0 * k, {"b", "a"}));
    }
  }
  const double now = scene.Clock("a", 30.0);
  ASSERT_TRUE(calibrated.RangeTo("b", now) && raw.RangeTo("b", now));
  // (a's clock, 80 ppm fast and not told here, makes the round trip 80 ppm long: 0.3 mm.)
  EXPECT_NEAR(calibrated.RangeTo("b", now)->range, 4.0, 1e-3);
  EXPECT_NEAR(raw.RangeTo("b", now)->range, 4.0 - o.offset, 1e-3);
}

TEST(TwoWayRangerTest, NoRangeUntilAnExchangeBothWays) {
  Scene scene(Pair(5.0));
  TwoWayRanger ranger("a", {"a", "b"}, RangerOptions{});
  for (int k = 0; k < 3; ++k) AddAll(ranger, scene.Send("a", static_cast<std::uint8_t>(k), 10.0 + 5.0 * k, {"a", "b"}));
  EXPECT_FALSE(ranger.RangeTo("b", scene.Clock("a", 30.0)));
  // b's packet heard by a, but b's own timing of it not (yet) shared: still none.
  AddAll(ranger, scene.Send("b", 9, 26.0, {"a"}));
  EXPECT_FALSE(ranger.RangeTo("b", scene.Clock("a", 30.0)));
  EXPECT_TRUE(ranger.Ranges(scene.Clock("a", 30.0)).empty());
  // Its own timing comes: the exchange is whole.
  AddAll(ranger, scene.Send("b", 9, 26.0, {"b"}));
  ASSERT_TRUE(ranger.RangeTo("b", scene.Clock("a", 30.0)));
  EXPECT_NEAR(ranger.RangeTo("b", scene.Clock("a", 30.0))->range, 5.0, 1e-3);
}

// One exchange is one sample, whoever else timed its packets and in whatever order the
// timings come (a sample counted twice would halve the reported uncertainty).
TEST(TwoWayRangerTest, OneExchangeIsOneSample) {
  Scene scene({{"a", Robot{}}, {"b", Robot{4.0, 0.0, 3.0, 40e-6, 0.0}}, {"c", Robot{0.0, 3.0, -2.0, -30e-6, 0.0}}});
  TwoWayRanger ranger("a", {"a", "b", "c"}, RangerOptions{});
  AddAll(ranger, scene.Send("a", 1, 10.0, {"c", "a", "b"}));
  AddAll(ranger, scene.Send("b", 2, 12.0, {"b", "c", "a"}));
  ASSERT_TRUE(ranger.RangeTo("b", scene.Clock("a", 13.0)));
  EXPECT_EQ(ranger.RangeTo("b", scene.Clock("a", 13.0))->samples, 1);
  TwoWayRanger other_order("a", {"a", "b", "c"}, RangerOptions{});
  AddAll(other_order, scene.Send("a", 1, 10.0, {"a", "b", "c"}));
  AddAll(other_order, scene.Send("b", 2, 12.0, {"a", "c", "b"}));
  ASSERT_TRUE(other_order.RangeTo("b", scene.Clock("a", 13.0)));
  EXPECT_EQ(other_order.RangeTo("b", scene.Clock("a", 13.0))->samples, 1);
  EXPECT_NEAR(other_order.RangeTo("b", scene.Clock("a", 13.0))->range, 4.0, 1e-3);
}

TEST(TwoWayRangerTest, ExchangesFurtherApartThanTheWindowArePairedWithNothing) {
  Scene scene(Pair(5.0));
  RangerOptions o;
  o.pair_window = 3.0;
  TwoWayRanger ranger("a", {"a", "b"}, o);
  AddAll(ranger, scene.Send("a", 1, 10.0, {"a", "b"}));
  AddAll(ranger, scene.Send("b", 1, 14.0, {"b", "a"}));
  EXPECT_FALSE(ranger.RangeTo("b", scene.Clock("a", 15.0)));
  AddAll(ranger, scene.Send("a", 2, 16.0, {"a", "b"}));
  EXPECT_TRUE(ranger.RangeTo("b", scene.Clock("a", 17.0)));
}

TEST(TwoWayRangerTest, ATeamOfFourRangesEveryPairWithTimingNoise) {
  std::map<std::string, Robot> robots = {{"r0", Robot{0.0, 0.0, 10.0, 50e-6, 0.0}},
                                         {"r1", Robot{3.0, 4.0, -7.0, -90e-6, 0.0}},
                                         {"r2", Robot{-6.0, 1.0, 100.0, 10e-6, 0.0}},
                                         {"r3", Robot{2.0, -9.0, 0.5, 150e-6, 0.0}}};
  Scene scene(robots, 10e-6, 5);
  const std::vector<std::string> team = {"r0", "r1", "r2", "r3"};
  std::map<std::string, std::unique_ptr<TwoWayRanger>> rangers;
  for (const std::string& r : team) rangers[r] = std::make_unique<TwoWayRanger>(r, team, RangerOptions{});
  double t = 5.0;
  for (int round = 0; round < 6; ++round) {
    for (const std::string& s : team) {
      const std::vector<Timing> timings = scene.Send(s, static_cast<std::uint8_t>(round), t, team);
      for (auto& [name, ranger] : rangers) AddAll(*ranger, timings);
      t += 2.2;
    }
  }
  for (const std::string& me : team) {
    const std::vector<Range> ranges = rangers[me]->Ranges(scene.Clock(me, t));
    ASSERT_EQ(ranges.size(), 3u) << me;
    for (const Range& r : ranges) {
      EXPECT_NEAR(r.range, scene.Distance(me, r.teammate), 0.01) << me << " to " << r.teammate;
      EXPECT_GT(r.range_std, 0.0);
      EXPECT_LT(r.range_std, 0.05);
      EXPECT_GE(r.age, 0.0);
    }
    EXPECT_EQ(rangers[me]->refused().total(), 0u) << me;
  }
}

TEST(TwoWayRangerTest, LostPacketsAndCollisionsOnlyCostSamples) {
  Scene scene(Pair(6.0), 0.0);
  TwoWayRanger ranger("a", {"a", "b"}, RangerOptions{});
  // b misses a's first packet (a collision there); a misses b's second; the rest gets through.
  AddAll(ranger, scene.Send("a", 0, 10.0, {"a"}));
  AddAll(ranger, scene.Send("b", 0, 12.0, {"b", "a"}));
  AddAll(ranger, scene.Send("a", 1, 14.0, {"a", "b"}));
  AddAll(ranger, scene.Send("b", 1, 16.0, {"b"}));
  AddAll(ranger, scene.Send("a", 2, 18.0, {"a", "b"}));
  // Whole exchanges: a's packet 1 with b's 0, and a's 2 with b's 0 too (within the window).
  const auto r = ranger.RangeTo("b", scene.Clock("a", 20.0));
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->range, 6.0, 1e-3);
  EXPECT_EQ(r->samples, 2);
}

TEST(TwoWayRangerTest, BadReportsAreCountedAndNeverMakeARange) {
  Scene scene(Pair(2.0));
  TwoWayRanger ranger("a", {"a", "b"}, RangerOptions{});
  // From a robot outside the team, and about one.
  std::vector<Timing> stranger = scene.Send("a", 1, 10.0, {"a"});
  stranger[0].listener = "mallory";
  ranger.Add(stranger[0]);
  stranger[0].listener = "a";
  stranger[0].sender = "mallory";
  ranger.Add(stranger[0]);
  EXPECT_EQ(ranger.refused().unknown_robot, 2u);
  // A clock that runs backwards, and one that is not a number.
  AddAll(ranger, scene.Send("a", 2, 20.0, {"a", "b"}));
  AddAll(ranger, scene.Send("b", 2, 20.5, {"b"}));
  std::vector<Timing> back = scene.Send("b", 3, 15.0, {"b", "a"});
  ranger.Add(back[0]);
  back[1].arrival = NAN;  // (NaN on a robot's own timing is an announcement, not a timing)
  ranger.Add(back[1]);
  EXPECT_EQ(ranger.refused().backwards, 2u);
  // A rate beyond any sound card's.
  std::vector<Timing> fast = scene.Send("b", 4, 21.0, {"b", "a"});
  fast[1].rate_error = 0.01;
  AddAll(ranger, fast);
  fast[1].rate_error = INFINITY;
  ranger.Add(fast[1]);
  EXPECT_EQ(ranger.refused().bad_rate, 2u);
  EXPECT_FALSE(ranger.RangeTo("b", scene.Clock("a", 25.0)));
}

// b sends the same payload twice within the window: a cannot tell which of its timings goes
// with which of b's, so neither is used; fresh payloads range again.
TEST(TwoWayRangerTest, APayloadSeenTwiceInTheWindowIsSkipped) {
  Scene scene(Pair(3.0));
  TwoWayRanger ranger("a", {"a", "b"}, RangerOptions{});
  AddAll(ranger, scene.Send("a", 1, 10.0, {"a", "b"}));
  const std::vector<Timing> first = scene.Send("b", 7, 11.0, {"b", "a"});
  const std::vector<Timing> second = scene.Send("b", 7, 13.0, {"b", "a"});
  // a hears the second copy only; b's own timing of the first arrives, then the second's.
  ranger.Add(first[0]);
  ranger.Add(second[1]);
  ranger.Add(second[0]);
  EXPECT_EQ(ranger.refused().repeated_payload, 1u);
  // The pair (first's b timing, second's a timing) would have been 343 m / 2 s off; it must not
  // have been kept as a range.
  const auto wrong = ranger.RangeTo("b", scene.Clock("a", 14.0));
  EXPECT_TRUE(!wrong || std::abs(wrong->range - 3.0) < 1e-2);
  // A report given twice as it was is not a repeat.
  ranger.Add(second[1]);
  EXPECT_EQ(ranger.refused().repeated_payload, 1u);
  AddAll(ranger, scene.Send("a", 2, 15.0, {"a", "b"}));
  AddAll(ranger, scene.Send("b", 8, 16.0, {"b", "a"}));
  const auto r = ranger.RangeTo("b", scene.Clock("a", 17.0));
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->range, 3.0, 1e-3);
}

// b's sound card failed and was reopened: its clock restarted, so its timings from before
// pair with nothing after; a timing on the old clock arriving late is refused.
TEST(TwoWayRangerTest, AClockThatRestartsPairsOnlyWithinItsLife) {
  Scene scene(Pair(4.0));
  TwoWayRanger ranger("a", {"a", "b"}, RangerOptions{});
  AddAll(ranger, scene.Send("a", 1, 10.0, {"a", "b"}));
  std::vector<Timing> reply = scene.Send("b", 1, 11.0, {"b", "a"});
  reply[0].clock_epoch = 1;  // b's own timing, on its new clock, which now reads 1000 s less
  reply[0].arrival -= 1000.0;
  AddAll(ranger, reply);
  EXPECT_FALSE(ranger.RangeTo("b", scene.Clock("a", 12.0)));  // its hearing of a's 1 was on the old clock
  std::vector<Timing> stale = scene.Send("a", 9, 11.5, {"b"});
  ranger.Add(stale[0]);  // epoch 0: older than b's clock now
  EXPECT_EQ(ranger.refused().backwards, 1u);
  std::vector<Timing> again = scene.Send("a", 2, 13.0, {"a", "b"});
  again[1].clock_epoch = 1;
  again[1].arrival -= 1000.0;
  AddAll(ranger, again);
  const auto r = ranger.RangeTo("b", scene.Clock("a", 14.0));
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->range, 4.0, 1e-3);
}

TEST(TwoWayRangerTest, ReceptionsAreToldTheirSenderByItsAnnouncementOrItsOwnTiming) {
  Scene scene(Pair(4.0));
  TwoWayRanger ranger("a", {"a", "b", "c"}, RangerOptions{});
  const std::vector<std::uint8_t> payload = {'b', 7, 0xAB, 0xCD};
  EXPECT_FALSE(ranger.SenderOf(payload));
  Timing announcement;
  announcement.sender = announcement.listener = "b";
  announcement.data = payload;
  announcement.arrival = NAN;
  ranger.Add(announcement);
  ASSERT_TRUE(ranger.SenderOf(payload));
  EXPECT_EQ(*ranger.SenderOf(payload), "b");
  EXPECT_EQ(ranger.refused().total(), 0u);
  // Its own timing tells the same; a second robot sending the same payload makes it unknown.
  AddAll(ranger, scene.Send("b", 8, 10.0, {"b"}));
  EXPECT_EQ(*ranger.SenderOf({'b', 8, 0xAB, 0xCD}), "b");
  announcement.sender = announcement.listener = "c";
  ranger.Add(announcement);
  EXPECT_FALSE(ranger.SenderOf(payload));
}

// A robot that says the same every few seconds (a wanderer's announcement): with stamps, each
// sending is a packet of its own, and the ranges are right; without, they are skipped.
TEST(TwoWayRangerTest, ThePayloadSentAgainIsAPacketOfItsOwnByItsStamps) {
  Scene scene(Pair(5.0));
  TwoWayRanger stamped("a", {"a", "b"}, RangerOptions{}), unstamped("a", {"a", "b"}, RangerOptions{});
  for (int k = 0; k < 4; ++k) {
    const double t = 10.0 + 5.0 * k;
    std::vector<Timing> mine = scene.Send("a", 1, t, {"a", "b"}), theirs = scene.Send("b", 1, t + 2.0, {"b", "a"});
    for (TwoWayRanger* r : {&stamped, &unstamped}) {
      for (Timing timing : mine) {
        if (r == &stamped) timing.stamp = 1.7e9 + t + 0.05;
        r->Add(timing);
      }
      for (Timing timing : theirs) {
        if (r == &stamped) timing.stamp = 1.7e9 + t + 2.0 + 0.05;
        r->Add(timing);
      }
    }
  }
  const auto r = stamped.RangeTo("b", scene.Clock("a", 30.0));
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->range, 5.0, 1e-3);
  EXPECT_EQ(stamped.refused().total(), 0u);
  const auto skipped = unstamped.RangeTo("b", scene.Clock("a", 30.0));
  EXPECT_TRUE(!skipped || std::abs(skipped->range - 5.0) < 1e-3);
  EXPECT_GT(unstamped.refused().repeated_payload, 0u);
}

TEST(TwoWayRangerTest, ImpossibleOptionsAreRefusedByName) {
  auto refuses = [](RangerOptions o, const std::string& field) {
    try {
      TwoWayRanger r("a", {"a"}, o);
      ADD_FAILURE() << field << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  RangerOptions o;
  o.speed_of_sound = 0.0;
  refuses(o, "speed_of_sound");
  o = {};
  o.pair_window = -1.0;
  refuses(o, "pair_window");
  o = {};
  o.max_rate_error = NAN;
  refuses(o, "max_rate_error");
  o = {};
  o.samples = 0;
  refuses(o, "samples");
  o = {};
  o.sample_std = 0.0;
  refuses(o, "sample_std");
  EXPECT_THROW(TwoWayRanger("", {"a"}, RangerOptions{}), std::invalid_argument);
}

TEST(TwoWayRangerTest, OldSamplesAgeOut) {
  Scene scene(Pair(2.0));
  RangerOptions o;
  o.max_age = 10.0;
  TwoWayRanger ranger("a", {"a", "b"}, o);
  AddAll(ranger, scene.Send("a", 1, 10.0, {"a", "b"}));
  AddAll(ranger, scene.Send("b", 1, 11.0, {"b", "a"}));
  const auto fresh = ranger.RangeTo("b", scene.Clock("a", 13.0));
  ASSERT_TRUE(fresh);
  EXPECT_NEAR(fresh->age, 2.0, 0.01);
  EXPECT_FALSE(ranger.RangeTo("b", scene.Clock("a", 30.0)));
}

}  // namespace
}  // namespace ranging
