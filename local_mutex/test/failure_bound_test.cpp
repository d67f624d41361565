#include "local_mutex/failure_bound.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "local_mutex/scenarios.h"

namespace local_mutex {
namespace {

TEST(FailureBound, WilsonIntervalHoldsTheRateAndIsNotEmptyAtZero) {
  const Proportion none = WilsonInterval(0, 3000);
  EXPECT_EQ(none.rate, 0.0);
  EXPECT_EQ(none.low, 0.0);
  EXPECT_GT(none.high, 0.0);
  EXPECT_LT(none.high, 1.5e-3);  // 3000 grants resolve a rate of 1e-3
  const Proportion some = WilsonInterval(30, 1000);
  EXPECT_NEAR(some.rate, 0.03, 1e-12);
  EXPECT_LT(some.low, 0.03);
  EXPECT_GT(some.high, 0.03);
  EXPECT_NEAR(some.low, 0.0211, 2e-4);  // the score interval's textbook value for 30 of 1000
  EXPECT_NEAR(some.high, 0.0425, 2e-4);
  const Proportion all = WilsonInterval(10, 10);
  EXPECT_EQ(all.high, 1.0);
  EXPECT_LT(all.low, 1.0);
  EXPECT_THROW(WilsonInterval(3, 2), std::invalid_argument);
}

TEST(FailureBound, RequestsForChoosesTheFewestThatMeetRho) {
  EXPECT_EQ(RequestsFor(1e-3, 0.1), 3);
  EXPECT_EQ(RequestsFor(1e-3, 0.5), 10);  // 2^-10 < 1e-3 < 2^-9
  EXPECT_EQ(RequestsFor(0.5, 0.5), 1);
  EXPECT_EQ(RequestsFor(1e-3, 0.0), 1);
  EXPECT_EQ(RequestsFor(1e-3, 1.0), 0);  // nothing ever gets through
  for (const double p : {0.01, 0.2, 0.37, 0.9}) {
    const int n = RequestsFor(1e-4, p);
    EXPECT_LE(std::pow(p, n), 1e-4 * (1.0 + 1e-12)) << p;
    EXPECT_GT(std::pow(p, n - 1), 1e-4) << p;
  }
  EXPECT_THROW(RequestsFor(1e-3, 1.5), std::invalid_argument);
  EXPECT_THROW(RequestsFor(1.0, 0.5), std::invalid_argument);
}

TEST(FailureBound, NRequestsFitInOneGrabTime) {
  MutexOptions base;
  for (int n = 1; n <= 6; ++n) {
    const MutexOptions o = WithRequestsPerGrab(base, n);
    EXPECT_LT(n * o.request_mean, base.grab_time);
    EXPECT_GT((n + 1) * o.request_mean, base.grab_time);
    EXPECT_LE(o.lock_mean, o.request_mean);
    EXPECT_NO_THROW(ValidateMutexOptions(o));
  }
  EXPECT_THROW(WithRequestsPerGrab(base, 0), std::invalid_argument);
}

TrialOptions TwoInEarshot() {
  TrialOptions t;
  t.min_robots = t.max_robots = 2;
  return t;
}

// The bookkeeping of p_r and q_r: every request sent offers one copy to the other robot, which
// hears it unless the reception is lost or corrupted, and hears it sound unless it is lost.
TEST(FailureBound, RequestCopiesCountWhatReachedARobotInRange) {
  auto model = OpenFloor();
  const TrialSummary clean = RunTrials(*model, TwoInEarshot(), {}, 20);
  EXPECT_GT(clean.request_copies.offered, 20u);
  EXPECT_LE(clean.request_copies.heard, clean.request_copies.offered);
  EXPECT_LT(RequestLoss(clean.request_copies), 0.2);  // a few collide; most arrive
  EXPECT_GE(clean.request_copies.sounded, clean.request_copies.heard);  // a collision still sounds
  EXPECT_LE(RequestSilence(clean.request_copies), RequestLoss(clean.request_copies));

  TeamSimOptions deaf;
  deaf.loss = 1.0;
  const TrialSummary lost = RunTrials(*model, TwoInEarshot(), deaf, 20);
  EXPECT_GT(lost.request_copies.offered, 0u);
  EXPECT_EQ(lost.request_copies.heard, 0u);
  EXPECT_EQ(RequestLoss(lost.request_copies), 1.0);
  EXPECT_EQ(RequestSilence(lost.request_copies), 1.0);  // not even a carrier

  TeamSimOptions garbled;
  garbled.noise = 1.0;  // every packet heard as noise: a carrier, never a request
  const TrialSummary noisy = RunTrials(*model, TwoInEarshot(), garbled, 20);
  EXPECT_EQ(noisy.request_copies.heard, 0u);
  EXPECT_GT(noisy.request_copies.offered, 0u);
  // ...which the lock takes as a reason to wait: those copies sounded.
  EXPECT_LT(RequestSilence(noisy.request_copies), 0.2);

  TeamSimOptions half;
  half.noise = 0.5;
  const TrialSummary some = RunTrials(*model, TwoInEarshot(), half, 100);
  EXPECT_NEAR(RequestLoss(some.request_copies), 0.5, 0.12);
}

// A robot out of everyone's range is offered nothing: its requests count for nobody.
TEST(FailureBound, RobotsOutOfRangeAreOfferedNoCopies) {
  audio_propagation::PropagationOptions hearing;
  hearing.threads = 1;
  hearing.max_range = 5.0;  // m
  const audio_propagation::PropagationModel model(OpenFloorMap(20.0), hearing);
  const Eigen::Vector2d centre(10.0, 10.0);
  std::vector<TeamRobot> team(2);
  team[0] = {1, centre + Eigen::Vector2d(-9.0, -9.0), {{0.0, 0, 10.0}}};
  team[1] = {2, centre + Eigen::Vector2d(9.0, 9.0), {{0.0, 0, 10.0}}};
  TeamSim sim(model, team, {});
  sim.Run(600.0);
  ASSERT_FALSE(sim.InRange(0, 1));
  EXPECT_EQ(sim.request_copies().offered, 0u);
  EXPECT_EQ(sim.request_copies().heard, 0u);
  EXPECT_EQ(sim.request_copies().sounded, 0u);
  EXPECT_EQ(RequestLoss(sim.request_copies()), 0.0);  // nothing offered, nothing lost
}

}  // namespace
}  // namespace local_mutex
