#include "charging_demo/charging_behaviour.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace charging_demo {
namespace {

using Motion = ChargingCommand::Motion;
using local_mutex::State;

ChargingOptions Options() {
  ChargingOptions o;
  o.chargers = {100, 101};
  return o;
}

ChargingInputs At(double x, double y, double battery, double time, State lock = State::kReleased) {
  ChargingInputs in;
  in.odom = {x, y, 0.0};
  in.battery = battery;
  in.time = time;
  in.lock = lock;
  return in;
}

// The inputs with the charger at (3, 0) in sight (the robot faces +x), as the camera reports it
// every frame while it is in view.
ChargingInputs Seeing(ChargingInputs in) {
  const double dx = 3.0 - in.odom.x, dy = 0.0 - in.odom.y;
  in.sightings.push_back({100, std::hypot(dx, dy), std::atan2(dy, dx) - in.odom.yaw});
  return in;
}

TEST(ChargingBehaviour, FullCycleDutyToChargeAndBack) {
  ChargingBehaviour b(Options());
  ChargingCommand c = b.Update(At(0, 0, 0.5, 0.0));
  EXPECT_EQ(b.phase(), Phase::kDuty);
  EXPECT_EQ(c.motion, Motion::kDuty);
  EXPECT_FALSE(c.want_lock);

  c = b.Update(At(0, 0, 0.25, 1.0));  // low, no charger known yet: keep exploring
  EXPECT_EQ(b.phase(), Phase::kSeek);
  EXPECT_EQ(c.motion, Motion::kDuty);

  ChargingInputs in = At(0, 0, 0.25, 2.0);
  in.sightings = {{7, 2.0, 1.0}, {100, 3.0, 0.0}};  // a non-charger marker, and a charger 3 m ahead
  c = b.Update(in);
  EXPECT_EQ(b.phase(), Phase::kApproach);
  EXPECT_EQ(c.motion, Motion::kGoTo);
  EXPECT_NEAR(c.target.x(), 2.0, 1e-9);  // 1 m short of the charger, on the robot's side
  EXPECT_NEAR(c.target.y(), 0.0, 1e-9);
  EXPECT_FALSE(c.want_lock);

  in = At(1.9, 0.0, 0.24, 10.0);  // at the waiting point, the charger still in sight
  in.sightings = {{100, 1.1, 0.0}};
  c = b.Update(in);
  EXPECT_EQ(b.phase(), Phase::kWait);
  EXPECT_EQ(c.motion, Motion::kStop);
  EXPECT_TRUE(c.want_lock);
  for (State s : {State::kWanted, State::kSilent, State::kWanted}) {
    c = b.Update(Seeing(At(1.9, 0.0, 0.24, 30.0, s)));
    EXPECT_EQ(c.motion, Motion::kStop) << "moved while the lock was only wanted";
    EXPECT_TRUE(c.want_lock);
  }

  c = b.Update(Seeing(At(1.9, 0.0, 0.23, 50.0, State::kHeld)));
  EXPECT_EQ(b.phase(), Phase::kDock);
  EXPECT_EQ(c.motion, Motion::kGoTo);
  EXPECT_NEAR(c.target.x(), 3.0, 1e-9);

  ChargingInputs docked = Seeing(At(2.95, 0.0, 0.23, 60.0, State::kHeld));
  docked.docked = true;
  c = b.Update(docked);
  EXPECT_EQ(b.phase(), Phase::kCharge);
  EXPECT_EQ(c.motion, Motion::kStop);
  EXPECT_TRUE(c.want_lock);
  EXPECT_EQ(b.charges(), 1u);

  docked.battery = 0.99;
  docked.time = 600.0;
  c = b.Update(docked);
  EXPECT_EQ(b.phase(), Phase::kUndock);
  EXPECT_EQ(c.motion, Motion::kBackAway);
  EXPECT_TRUE(c.want_lock);  // released only once away from the charger

  c = b.Update(Seeing(At(1.9, 0.0, 0.99, 610.0, State::kHeld)));
  EXPECT_EQ(b.phase(), Phase::kDuty);
  EXPECT_EQ(c.motion, Motion::kDuty);
  EXPECT_FALSE(c.want_lock);
}

// Drives the behaviour to the waiting point of the charger 3 m ahead.
ChargingBehaviour Waiting(const ChargingOptions& o) {
  ChargingBehaviour b(o);
  ChargingInputs in = At(0, 0, 0.2, 0.0);
  in.sightings = {{100, 3.0, 0.0}};
  b.Update(in);
  b.Update(Seeing(At(2.0, 0.0, 0.2, 5.0, State::kWanted)));
  EXPECT_EQ(b.phase(), Phase::kWait);
  return b;
}

TEST(ChargingBehaviour, GivesUpOnALockThatNeverComesAndAvoidsThatCharger) {
  ChargingOptions o = Options();
  o.lock_timeout = 100.0;
  o.avoid_time = 200.0;
  ChargingBehaviour b = Waiting(o);
  ChargingCommand c = b.Update(Seeing(At(2.0, 0.0, 0.2, 104.0, State::kWanted)));
  EXPECT_EQ(b.phase(), Phase::kWait);
  c = b.Update(Seeing(At(2.0, 0.0, 0.2, 106.0, State::kWanted)));
  EXPECT_EQ(b.phase(), Phase::kSeek);
  EXPECT_FALSE(c.want_lock);  // the request is withdrawn
  EXPECT_EQ(b.give_ups(), 1u);
  c = b.Update(Seeing(At(2.0, 0.0, 0.2, 150.0)));
  EXPECT_EQ(b.phase(), Phase::kSeek);  // the only known charger is avoided
  ChargingInputs in = At(2.0, 0.0, 0.2, 160.0);
  in.sightings = {{101, 4.0, M_PI / 2}};  // another charger, 4 m to the left
  c = b.Update(in);
  EXPECT_EQ(b.phase(), Phase::kApproach);
  EXPECT_NEAR(c.target.x(), 2.0, 1e-9);
  EXPECT_NEAR(c.target.y(), 3.0, 1e-9);
}

// An approach that makes no progress for approach_timeout gives up: the charger is avoided for a
// while, and kept in memory.
TEST(ChargingBehaviour, AnApproachThatGetsNowhereGivesUp) {
  ChargingBehaviour b(Options());
  ChargingInputs in = At(0, 0, 0.9, 0.0);
  in.sightings = {{100, 3.0, 0.0}};  // charger at (3, 0)
  b.Update(in);
  b.Update(At(0, 0, 0.2, 100.0));
  ASSERT_EQ(b.phase(), Phase::kApproach);
  for (double t = 101.0; t <= 190.0; t += 1.0) b.Update(At(0.0, 0.5, 0.2, t));  // stuck 3 m off
  EXPECT_EQ(b.phase(), Phase::kApproach);
  b.Update(At(0.0, 0.5, 0.2, 191.0));
  EXPECT_EQ(b.phase(), Phase::kSeek);
  EXPECT_EQ(b.give_ups(), 1u);
  EXPECT_EQ(b.known_chargers().size(), 1u);
  b.Update(At(0.0, 0.5, 0.2, 192.0));
  EXPECT_EQ(b.phase(), Phase::kSeek);  // avoided: not approached again at once
}

TEST(ChargingBehaviour, NeverDocksWithoutTheLock) {
  ChargingBehaviour b = Waiting(Options());
  b.Update(Seeing(At(2.0, 0.0, 0.2, 10.0, State::kHeld)));
  EXPECT_EQ(b.phase(), Phase::kDock);
  // The lock is not held any more (lost in a noise storm): stand still and ask again.
  ChargingCommand c = b.Update(Seeing(At(2.3, 0.0, 0.2, 11.0, State::kWanted)));
  EXPECT_EQ(b.phase(), Phase::kWait);
  EXPECT_EQ(c.motion, Motion::kStop);
  EXPECT_TRUE(c.want_lock);
  c = b.Update(Seeing(At(2.3, 0.0, 0.2, 12.0, State::kHeld)));
  EXPECT_EQ(b.phase(), Phase::kDock);
  EXPECT_EQ(c.motion, Motion::kGoTo);
}

TEST(ChargingBehaviour, ADockThatTakesTooLongBacksOutAndTriesAgainHoldingTheLock) {
  ChargingOptions o = Options();
  o.dock_timeout = 30.0;
  ChargingBehaviour b = Waiting(o);
  b.Update(Seeing(At(2.0, 0.0, 0.2, 10.0, State::kHeld)));
  ChargingCommand c = b.Update(Seeing(At(2.8, 0.0, 0.2, 41.0, State::kHeld)));  // not docked after 31 s
  EXPECT_EQ(b.phase(), Phase::kUndock);
  EXPECT_EQ(c.motion, Motion::kBackAway);
  EXPECT_TRUE(c.want_lock);
  EXPECT_EQ(b.redocks(), 1u);
  c = b.Update(Seeing(At(1.8, 0.0, 0.2, 50.0, State::kHeld)));
  EXPECT_EQ(b.phase(), Phase::kDock);
  EXPECT_EQ(c.motion, Motion::kGoTo);
  EXPECT_TRUE(c.want_lock);
}

TEST(ChargingBehaviour, GivesUpAfterMaxRedocksInARow) {
  ChargingOptions o = Options();
  o.dock_timeout = 30.0;
  o.max_redocks = 1;
  ChargingBehaviour b = Waiting(o);
  b.Update(Seeing(At(2.0, 0.0, 0.2, 10.0, State::kHeld)));
  b.Update(Seeing(At(2.8, 0.0, 0.2, 41.0, State::kHeld)));    // first timeout: back out, retry
  b.Update(Seeing(At(1.8, 0.0, 0.2, 50.0, State::kHeld)));
  EXPECT_EQ(b.phase(), Phase::kDock);
  b.Update(Seeing(At(2.8, 0.0, 0.2, 81.0, State::kHeld)));    // second: back out for good
  EXPECT_EQ(b.phase(), Phase::kUndock);
  ChargingCommand c = b.Update(Seeing(At(1.8, 0.0, 0.2, 90.0, State::kHeld)));
  EXPECT_EQ(b.phase(), Phase::kSeek);
  EXPECT_FALSE(c.want_lock);  // released once clear of the charger
  EXPECT_EQ(b.redocks(), 2u);
  EXPECT_EQ(b.give_ups(), 1u);
}

TEST(ChargingBehaviour, ForgetsARememberedChargerThatIsNotThere) {
  ChargingBehaviour b(Options());
  ChargingInputs in = At(0, 0, 0.9, 0.0);
  in.sightings = {{100, 4.0, 0.0}};  // seen on duty, 4 m ahead
  b.Update(in);
  ASSERT_EQ(b.known_chargers().size(), 1u);
  ChargingCommand c = b.Update(At(0, 0, 0.2, 100.0));
  EXPECT_EQ(b.phase(), Phase::kApproach);  // goes where memory says
  EXPECT_NEAR(c.target.x(), 3.0, 1e-9);
  // Odometry drifted: near the remembered spot there is nothing in sight.
  b.Update(At(2.5, 0.0, 0.2, 110.0));
  EXPECT_EQ(b.phase(), Phase::kApproach);  // not for recheck_time yet
  c = b.Update(At(2.6, 0.0, 0.2, 116.0));
  EXPECT_EQ(b.phase(), Phase::kSeek);
  EXPECT_EQ(c.motion, Motion::kDuty);
  EXPECT_TRUE(b.known_chargers().empty());
  EXPECT_EQ(b.forgotten(), 1u);
}

// Behind a wall the remembered charger is out of view: being near it without seeing it is no
// reason to forget it, and reaching the ring there is not arriving.
TEST(ChargingBehaviour, OnTheRingBehindAWallIsNotThereYet) {
  ChargingBehaviour b(Options());
  ChargingInputs in = At(0, 0, 0.9, 0.0);
  in.sightings = {{100, 3.0, 0.0}};  // charger at (3, 0)
  b.Update(in);
  const auto wall = [](const Eigen::Vector2d&) { return false; };
  for (double t = 100.0; t <= 130.0; t += 1.0) {
    in = At(3.0, 1.0, 0.2, t);  // on the ring, the charger unseen
    in.in_view = wall;
    const ChargingCommand c = b.Update(in);
    EXPECT_EQ(b.phase(), Phase::kApproach) << t;
    EXPECT_EQ(c.motion, Motion::kGoTo);
    EXPECT_FALSE(c.want_lock);
  }
  EXPECT_EQ(b.known_chargers().size(), 1u);
  EXPECT_EQ(b.forgotten(), 0u);
  // In view and still unseen: it is not there after all.
  in = At(3.0, 1.0, 0.2, 131.0);
  in.in_view = [](const Eigen::Vector2d&) { return true; };
  b.Update(in);
  in.time = 137.0;
  b.Update(in);
  EXPECT_TRUE(b.known_chargers().empty());
  EXPECT_EQ(b.phase(), Phase::kSeek);
}

TEST(ChargingBehaviour, LetsGoOfTheLockWhenTheChargerWaitedAtIsNotInSight) {
  ChargingBehaviour b = Waiting(Options());  // charger seen at t = 0, waiting since t = 5
  ChargingCommand c = b.Update(At(2.0, 0.0, 0.2, 5.5, State::kHeld));
  EXPECT_EQ(b.phase(), Phase::kDock);
  c = b.Update(At(2.1, 0.0, 0.2, 11.0, State::kHeld));  // not seen for 11 s, 0.9 m away
  EXPECT_EQ(b.phase(), Phase::kSeek);
  EXPECT_FALSE(c.want_lock);
  EXPECT_TRUE(b.known_chargers().empty());
}

// Seen again long after, 1.5 m from where memory has it: the same charger, drifted, not a second.
TEST(ChargingBehaviour, ADriftedChargerIsRememberedOnce) {
  ChargingBehaviour b(Options());
  ChargingInputs in = At(0, 0, 0.9, 0.0);
  in.sightings = {{100, 3.0, 0.0}};
  b.Update(in);
  in = At(0, 0, 0.9, 600.0);
  in.sightings = {{100, 4.5, 0.0}};
  b.Update(in);
  ASSERT_EQ(b.known_chargers().size(), 1u);
  EXPECT_NEAR(b.known_chargers()[0].x(), 4.5, 1e-9);
  // Two chargers seen together 1.5 m apart are two.
  in.time = 601.0;
  in.sightings = {{100, 4.5, 0.0}, {101, 6.0, 0.0}};
  b.Update(in);
  EXPECT_EQ(b.known_chargers().size(), 2u);
}

TEST(ChargingBehaviour, TheChargerInUseFollowsItsSightings) {
  ChargingBehaviour b = Waiting(Options());
  ChargingInputs in = At(2.0, 0.0, 0.2, 10.0, State::kHeld);
  in.sightings = {{100, 1.0, 0.3}};  // seen 0.3 rad to the left now (odometry drifted)
  ChargingCommand c = b.Update(in);
  EXPECT_EQ(b.phase(), Phase::kDock);
  EXPECT_NEAR(c.target.x(), 2.0 + std::cos(0.3), 1e-9);
  EXPECT_NEAR(c.target.y(), std::sin(0.3), 1e-9);
  EXPECT_EQ(b.known_chargers().size(), 1u);
}

TEST(ChargingBehaviour, WaitsAnywhereOnTheRing) {
  ChargingBehaviour b(Options());
  ChargingInputs in = At(0, 0, 0.2, 0.0);
  in.sightings = {{100, 3.0, 0.0}};  // charger at (3, 0)
  b.Update(in);
  // Coming round from above: the target is the ring's nearest point, and it waits there.
  in = At(3.0, 2.0, 0.2, 1.0);
  in.sightings = {{100, 2.0, -M_PI / 2}};
  ChargingCommand c = b.Update(in);
  EXPECT_EQ(b.phase(), Phase::kApproach);
  EXPECT_NEAR(c.target.x(), 3.0, 1e-9);
  EXPECT_NEAR(c.target.y(), 1.0, 1e-9);
  in = At(3.0, 1.1, 0.2, 5.0);
  in.sightings = {{100, 1.1, -M_PI / 2}};
  c = b.Update(in);
  EXPECT_EQ(b.phase(), Phase::kWait);
  EXPECT_EQ(c.motion, Motion::kStop);
}

TEST(ChargingBehaviour, HemmedInAfterChargingReleasesOnceOffTheCharger) {
  ChargingOptions o = Options();
  o.undock_timeout = 20.0;
  ChargingBehaviour b = Waiting(o);
  b.Update(Seeing(At(2.0, 0.0, 0.2, 10.0, State::kHeld)));
  ChargingInputs docked = Seeing(At(3.0, 0.0, 0.99, 20.0, State::kHeld));
  docked.docked = true;
  b.Update(docked);
  docked.time = 21.0;
  b.Update(docked);
  EXPECT_EQ(b.phase(), Phase::kUndock);
  // Waiting robots leave no room for a full metre: 0.6 m off is enough once the timeout passes.
  ChargingCommand c = b.Update(Seeing(At(2.4, 0.0, 0.99, 30.0, State::kHeld)));
  EXPECT_EQ(c.motion, Motion::kBackAway);
  ChargingInputs still_on = Seeing(At(2.8, 0.0, 0.99, 50.0, State::kHeld));  // 0.2 m off and docked
  still_on.docked = true;
  c = b.Update(still_on);
  EXPECT_EQ(b.phase(), Phase::kUndock) << "released while still on the charger";
  c = b.Update(Seeing(At(2.4, 0.0, 0.99, 52.0, State::kHeld)));
  EXPECT_EQ(b.phase(), Phase::kDuty);
  EXPECT_FALSE(c.want_lock);
}

TEST(ChargingBehaviour, RejectsImpossibleOptions) {
  ChargingOptions o = Options();
  o.chargers.clear();
  EXPECT_THROW(ChargingBehaviour{o}, std::invalid_argument);
  o = Options();
  o.low_battery = 1.2;
  EXPECT_THROW(ChargingBehaviour{o}, std::invalid_argument);
  o = Options();
  o.full_battery = 0.2;
  EXPECT_THROW(ChargingBehaviour{o}, std::invalid_argument);
  o = Options();
  o.wait_distance = 0.0;
  EXPECT_THROW(ChargingBehaviour{o}, std::invalid_argument);
  o = Options();
  o.max_redocks = -1;
  EXPECT_THROW(ChargingBehaviour{o}, std::invalid_argument);
}

}  // namespace
}  // namespace charging_demo
