#include "local_mutex/local_mutex.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace local_mutex {
namespace {

// One robot with scripted intervals (every Gaussian draw returns its mean) that records what it
// sends and every event.
struct Robot {
  std::vector<Message> sent;
  std::vector<MutexEvent> events;
  LocalMutex mutex;

  explicit Robot(int id, MutexOptions o = {})
      : mutex(WithId(o, id), [this](const std::vector<std::uint8_t>& p) { sent.push_back(*Decode(p)); },
              [](double mean, double) { return mean; }) {
    mutex.SetObserver([this](const MutexEvent& e) { events.push_back(e); });
  }
  static MutexOptions WithId(MutexOptions o, int id) {
    o.robot_id = id;
    return o;
  }
  // Ticks every 0.1 s from `from` up to `to` (inclusive).
  void RunTo(double from, double to) {
    for (int k = 0; from + 0.1 * k <= to + 1e-9; ++k) mutex.Tick(from + 0.1 * k);
  }
  void Hear(const Message& m, double now) { mutex.HearPacket(Encode(m), now); }
  // WANTED until a tick before `at`, HELD at `at`.
  void ExpectGrantAt(double from, double at) {
    RunTo(from, at - 0.1);
    EXPECT_EQ(mutex.state(), State::kWanted);
    mutex.Tick(at);
    EXPECT_EQ(mutex.state(), State::kHeld);
  }
};

TEST(LocalMutex, StartsReleasedAtClockZeroAndSaysNothing) {
  Robot r(11);
  EXPECT_EQ(r.mutex.state(), State::kReleased);
  EXPECT_EQ(r.mutex.clock(), 0);
  r.RunTo(0.0, 200.0);
  EXPECT_TRUE(r.sent.empty());
}

TEST(LocalMutex, AloneItRequestsEveryTRequestAndTakesTheLockAfterTGrabOfSilence) {
  Robot r(11);
  r.RunTo(0.0, 3.3);
  ASSERT_TRUE(r.mutex.Request(3.3));
  EXPECT_EQ(r.mutex.state(), State::kWanted);
  EXPECT_EQ(r.mutex.request().time, 0);
  r.RunTo(3.4, 43.2);
  EXPECT_EQ(r.mutex.state(), State::kWanted);
  ASSERT_EQ(r.sent.size(), 2u);  // at 18.3 and 33.3
  for (const Message& m : r.sent) EXPECT_EQ(m, (Message{11, MessageType::kRequest, 0}));  // same T_i
  EXPECT_EQ(r.mutex.clock(), 2);  // each send is an event
  r.mutex.Tick(43.3);
  EXPECT_EQ(r.mutex.state(), State::kHeld);
  EXPECT_NEAR(r.mutex.state_since(), 43.3, 1e-9);
  EXPECT_EQ(r.mutex.counters().grants, 1u);
  // A lock announcement at once, then every t_lock, stamped with the clock.
  ASSERT_EQ(r.sent.size(), 3u);
  EXPECT_EQ(r.sent[2], (Message{11, MessageType::kLock, 2}));
  r.RunTo(43.3, 73.3);
  ASSERT_EQ(r.sent.size(), 6u);
  EXPECT_EQ(r.sent[3], (Message{11, MessageType::kLock, 3}));
  EXPECT_EQ(r.sent[5], (Message{11, MessageType::kLock, 5}));
  ASSERT_TRUE(r.mutex.Release(80.0));
  r.RunTo(80.0, 200.0);
  EXPECT_EQ(r.sent.size(), 6u);
  EXPECT_EQ(r.mutex.state(), State::kReleased);
}

TEST(LocalMutex, AnyNoiseRestartsTheGrabTimerAndTicksTheClock) {
  Robot r(11);
  r.mutex.Request(0.0);
  r.mutex.HearNoise(10.0);
  EXPECT_EQ(r.mutex.clock(), 1);
  EXPECT_NEAR(r.mutex.grab_deadline(), 50.0, 1e-9);
  r.ExpectGrantAt(0.0, 50.0);
}

TEST(LocalMutex, APacketSetsTheClockPastItsStamp) {
  Robot r(11);
  r.mutex.HearNoise(0.0);
  r.mutex.HearNoise(0.1);
  r.mutex.HearNoise(0.2);  // clock 3
  r.Hear({40, MessageType::kLock, 10}, 1.0);
  EXPECT_EQ(r.mutex.clock(), 11);
  r.Hear({40, MessageType::kLock, 2}, 2.0);
  EXPECT_EQ(r.mutex.clock(), 12);
  EXPECT_EQ(r.mutex.state(), State::kReleased);  // RELEASED only keeps time
  EXPECT_TRUE(r.sent.empty());
}

TEST(LocalMutex, TheRequestTimeIsTheClockWhenWanted) {
  Robot r(212);
  r.Hear({11, MessageType::kRequest, 0}, 14.0);
  r.Hear({11, MessageType::kRequest, 0}, 29.0);
  r.mutex.Request(32.8);
  EXPECT_EQ(r.mutex.request().time, 2);
  EXPECT_EQ(r.mutex.request().robot_id, 212);
}

TEST(LocalMutex, ARequestWithPriorityDefersUsIntoSilence) {
  Robot r(30);
  r.mutex.Request(1.0);  // (0, 30)
  r.Hear({11, MessageType::kRequest, 0}, 5.0);  // (0, 11) precedes (0, 30)
  EXPECT_EQ(r.mutex.state(), State::kSilent);
  // POSTPONEREQUEST: no request for t_grab + t_request, the grab timer t_grab after that.
  EXPECT_NEAR(r.mutex.next_transmit(), 5.0 + 40.0 + 15.0, 1e-9);
  EXPECT_NEAR(r.mutex.grab_deadline(), 60.0 + 40.0, 1e-9);
  r.RunTo(5.0, 59.9);
  EXPECT_TRUE(r.sent.empty());
  r.mutex.Tick(60.0);
  ASSERT_EQ(r.sent.size(), 1u);
  EXPECT_EQ(r.sent[0], (Message{30, MessageType::kRequest, 0}));
  EXPECT_EQ(r.mutex.state(), State::kWanted);
  r.ExpectGrantAt(60.0, 100.0);
  EXPECT_EQ(r.mutex.counters().grants, 1u);
}

TEST(LocalMutex, ARecentRequestHeardBeforeWantingDefersUsFromTheStart) {
  Robot r(18);
  r.Hear({164, MessageType::kRequest, 0}, 43.0);
  r.mutex.Request(45.0);  // (1, 18) comes after (0, 164)
  EXPECT_EQ(r.mutex.state(), State::kSilent);
  EXPECT_NEAR(r.mutex.next_transmit(), 43.0 + 40.0 + 15.0, 1e-9);
  EXPECT_NEAR(r.mutex.grab_deadline(), 98.0 + 40.0, 1e-9);
  r.RunTo(45.0, 97.9);
  EXPECT_TRUE(r.sent.empty());
}

TEST(LocalMutex, AnOldRequestIsForgotten) {
  Robot r(18);
  r.Hear({164, MessageType::kRequest, 0}, 3.0);
  r.mutex.Request(45.0);  // more than t_grab later: 164 has had its turn
  EXPECT_EQ(r.mutex.state(), State::kWanted);
}

TEST(LocalMutex, ARequestWithoutPriorityOnlyRestartsTheGrabTimer) {
  Robot r(11);
  r.mutex.Request(0.0);  // (0, 11)
  r.Hear({30, MessageType::kRequest, 0}, 5.0);  // (0, 30) comes after us
  EXPECT_EQ(r.mutex.state(), State::kWanted);
  EXPECT_NEAR(r.mutex.grab_deadline(), 45.0, 1e-9);
  EXPECT_NEAR(r.mutex.next_transmit(), 15.0, 1e-9);
  r.Hear({40, MessageType::kRequest, 3}, 6.0);  // a later time loses whatever the id
  EXPECT_EQ(r.mutex.state(), State::kWanted);
}

TEST(LocalMutex, AnEarlierTimeWinsOverASmallerId) {
  Robot r(5);
  r.Hear({9, MessageType::kLock, 3}, 0.0);  // clock 4
  r.mutex.Request(1.0);                     // (4, 5)
  r.Hear({200, MessageType::kRequest, 2}, 2.0);
  EXPECT_EQ(r.mutex.state(), State::kSilent);
}

TEST(LocalMutex, ALockHeardKeepsUsRequesting) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.mutex.Tick(15.0);  // request sent; the next is due at 30
  ASSERT_EQ(r.sent.size(), 1u);
  r.Hear({11, MessageType::kLock, 5}, 20.0);
  EXPECT_NEAR(r.mutex.next_transmit(), 30.0, 1e-9);  // already sooner than 20 + 15
  EXPECT_NEAR(r.mutex.grab_deadline(), 60.0, 1e-9);
  EXPECT_EQ(r.mutex.state(), State::kWanted);
}

TEST(LocalMutex, ALockHeardWhileSilentBringsTheNextRequestForward) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.Hear({11, MessageType::kRequest, 0}, 5.0);  // silent until 60
  ASSERT_EQ(r.mutex.state(), State::kSilent);
  r.Hear({11, MessageType::kLock, 3}, 20.0);
  EXPECT_EQ(r.mutex.state(), State::kSilent);
  EXPECT_NEAR(r.mutex.next_transmit(), 35.0, 1e-9);
  EXPECT_NEAR(r.mutex.grab_deadline(), 75.0, 1e-9);  // t_grab after that request
}

TEST(LocalMutex, NoiseWhileSilentNeverLetsTheGrabTimerEndBeforeARequest) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.Hear({11, MessageType::kRequest, 0}, 5.0);  // next request at 60, grab at 100
  r.mutex.HearNoise(10.0);  // Program 7.2 alone would set the grab timer to 50
  EXPECT_NEAR(r.mutex.grab_deadline(), 100.0, 1e-9);
  r.RunTo(5.0, 59.9);
  EXPECT_EQ(r.mutex.state(), State::kSilent);
  EXPECT_TRUE(r.sent.empty());
}

TEST(LocalMutex, ASecondPriorRequestWhileSilentExtendsTheSilence) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.Hear({11, MessageType::kRequest, 0}, 5.0);
  r.Hear({11, MessageType::kRequest, 0}, 20.0);
  EXPECT_EQ(r.mutex.state(), State::kSilent);
  EXPECT_NEAR(r.mutex.next_transmit(), 75.0, 1e-9);
  EXPECT_NEAR(r.mutex.grab_deadline(), 115.0, 1e-9);
}

TEST(LocalMutex, HeldIgnoresEverythingButTheClock) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.RunTo(0.0, 40.0);
  ASSERT_EQ(r.mutex.state(), State::kHeld);
  const LamportTime before = r.mutex.clock();
  r.Hear({11, MessageType::kRequest, 0}, 41.0);
  r.Hear({12, MessageType::kLock, 0}, 42.0);
  r.mutex.HearNoise(43.0);
  EXPECT_EQ(r.mutex.state(), State::kHeld);
  EXPECT_EQ(r.mutex.clock(), before + 3);
}

TEST(LocalMutex, RequestAndReleaseAreIdempotentWhereTheyShouldBe) {
  Robot r(30);
  EXPECT_FALSE(r.mutex.Release(0.0));  // no-op while RELEASED
  EXPECT_TRUE(r.mutex.Request(0.0));
  EXPECT_FALSE(r.mutex.Request(1.0));  // already wanted: nothing changes
  EXPECT_NEAR(r.mutex.grab_deadline(), 40.0, 1e-9);
  r.RunTo(0.0, 40.0);
  ASSERT_EQ(r.mutex.state(), State::kHeld);
  EXPECT_FALSE(r.mutex.Request(41.0));  // held: stays held
  EXPECT_EQ(r.mutex.state(), State::kHeld);
}

TEST(LocalMutex, ReleaseWithdrawsAPendingRequest) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.mutex.Tick(15.0);
  ASSERT_TRUE(r.mutex.Release(20.0));
  r.RunTo(20.0, 100.0);
  EXPECT_EQ(r.sent.size(), 1u);
  EXPECT_EQ(r.mutex.state(), State::kReleased);
  // Wanting again asks with the clock of now.
  r.mutex.Request(101.0);
  EXPECT_EQ(r.mutex.request().time, 1);
}

TEST(LocalMutex, PacketsThatAreNotOursAreNoise) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.mutex.HearPacket({'W', 1, 2, 3}, 10.0);
  r.mutex.HearPacket({30, 'R', 0}, 11.0);
  EXPECT_EQ(r.mutex.counters().malformed, 2u);
  EXPECT_EQ(r.mutex.clock(), 2);
  EXPECT_NEAR(r.mutex.grab_deadline(), 51.0, 1e-9);
}

TEST(LocalMutex, AnotherRobotWithOurIdIsCountedAndTreatedAsNoise) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.Hear({30, MessageType::kRequest, 7}, 10.0);
  EXPECT_EQ(r.mutex.counters().duplicate_ids, 1u);
  EXPECT_EQ(r.mutex.clock(), 1);
  EXPECT_NEAR(r.mutex.grab_deadline(), 50.0, 1e-9);
  ASSERT_FALSE(r.events.empty());
  EXPECT_EQ(r.events.back().kind, MutexEvent::Kind::kDuplicateId);
}

TEST(LocalMutex, OurOwnEchoIsIgnored) {
  Robot r(30);
  r.mutex.Request(0.0);
  r.mutex.Tick(15.0);
  r.Hear({30, MessageType::kRequest, 0}, 15.5);  // what we just sent
  EXPECT_EQ(r.mutex.counters().echoes, 1u);
  EXPECT_EQ(r.mutex.counters().duplicate_ids, 0u);
  EXPECT_NEAR(r.mutex.grab_deadline(), 40.0, 1e-9);
  r.Hear({30, MessageType::kRequest, 0}, 25.0);  // too late to be an echo
  EXPECT_EQ(r.mutex.counters().duplicate_ids, 1u);
}

TEST(LocalMutex, ObserverSeesEveryStateChangeAndMessage) {
  Robot r(11);
  r.mutex.Request(0.0);
  r.RunTo(0.0, 50.0);
  std::vector<std::string> seen;
  for (const MutexEvent& e : r.events) {
    seen.push_back(std::string(EventKindName(e.kind)) + ":" + StateName(e.state));
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"state:WANTED", "sent:WANTED", "sent:WANTED", "state:HELD",
                                            "sent:HELD", "sent:HELD"}));
}

TEST(MutexOptions, ImpossibleTimersAreRefusedByName) {
  auto expect_error = [](MutexOptions o, const std::string& name) {
    try {
      LocalMutex m(o, [](const std::vector<std::uint8_t>&) {});
      ADD_FAILURE() << "accepted bad " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  MutexOptions o;
  o.grab_time = 0.0;
  expect_error(o, "grab_time");
  o = {};
  o.lock_mean = 40.0;  // t_lock >= t_grab
  expect_error(o, "lock_mean");
  o = {};
  o.request_mean = 50.0;
  expect_error(o, "request_mean");
  o = {};
  o.robot_id = 0;
  expect_error(o, "robot_id");
  o.robot_id = 256;
  expect_error(o, "robot_id");
  o = {};
  o.request_sd = -1.0;
  expect_error(o, "request_sd");
}

TEST(LocalMutex, DrawnIntervalsFollowTheirGaussians) {
  std::vector<double> gaps;
  double last = 0.0;
  MutexOptions o;
  o.robot_id = 3;
  o.seed = 7;
  double now = 0.0;
  LocalMutex m(o, [&](const std::vector<std::uint8_t>&) {
    gaps.push_back(now - last);
    last = now;
  });
  m.Request(0.0);
  // Someone holds the lock forever: we keep requesting without ever taking it.
  for (int k = 0; k < 200000; ++k) {
    now = k * 0.01;
    if (k % 500 == 0) m.HearPacket(Encode({9, MessageType::kLock, 1}), now);
    m.Tick(now);
  }
  ASSERT_GT(gaps.size(), 50u);
  double sum = 0.0;
  for (std::size_t k = 1; k < gaps.size(); ++k) sum += gaps[k];
  EXPECT_NEAR(sum / (gaps.size() - 1), 15.0, 1.0);
}

}  // namespace
}  // namespace local_mutex
