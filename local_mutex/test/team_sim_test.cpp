#include "local_mutex/team_sim.h"

#include <cstdio>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "flat_table.h"
#include "local_mutex/scenarios.h"
#include "local_mutex/timeline_plot.h"

namespace local_mutex {
namespace {

Eigen::Vector2d Centre(const audio_propagation::PropagationModel& model) {
  const grid::OccupancyMap& map = model.map();
  return map.CellCoordsToWorld({map.width() / 2.0, map.height() / 2.0});
}

// The thesis's three-robot trial, run to the end with every event recorded.
std::unique_ptr<TeamSim> RecordedThree(const audio_propagation::PropagationModel& model) {
  TeamSimOptions options;
  options.record = true;
  auto sim = std::make_unique<TeamSim>(model, ThreeScenario(Centre(model)), options);
  sim->Run(3600.0);
  return sim;
}

TEST(TeamSim, ARobotAloneGetsTheLockTGrabAfterWantingIt) {
  auto model = OpenFloor();
  TeamSim sim(*model, SingleScenario(Centre(*model)), {});
  sim.Run(3600.0);
  ASSERT_TRUE(sim.Done());
  ASSERT_EQ(sim.grants().size(), 1u);
  const Grant& g = sim.grants()[0];
  EXPECT_NEAR(g.wanted, 3.3, 0.06);
  EXPECT_NEAR(g.granted, 43.3, 1.0);  // the thesis's Figure 7.5(a)
  EXPECT_NEAR(g.released, 99.8, 0.2);
  EXPECT_EQ(g.request.time, 0);
  EXPECT_EQ(sim.violations(), 0u);
  // Requests every ~15 s while waiting, then announcements every ~10 s while held.
  EXPECT_GE(sim.mutex(0).counters().sent, 2u + 5u);
}

TEST(TeamSim, ThreeRobotsAreServedInTheOrderOfTheirRequests) {
  auto model = OpenFloor();
  const auto three = RecordedThree(*model);
  const TeamSim& sim = *three;
  ASSERT_TRUE(sim.Done());
  ASSERT_EQ(sim.grants().size(), 3u);
  const std::vector<int> order = {sim.robot(sim.grants()[0].robot).id, sim.robot(sim.grants()[1].robot).id,
                                  sim.robot(sim.grants()[2].robot).id};
  EXPECT_EQ(order, (std::vector<int>{11, 30, 212}));  // Table 7.1
  EXPECT_EQ(sim.grants()[0].request.time, 0);
  EXPECT_EQ(sim.grants()[1].request.time, 0);
  EXPECT_EQ(sim.grants()[2].request.time, 2);  // 212 heard two packets before it wanted the lock
  // The first grant t_grab after the last sound 11 heard (thesis: 44.6 s); each later one at
  // most t_grab after the previous holder's last announcement, which came at most t_lock
  // (+ 3 sd) before it let go.
  EXPECT_NEAR(sim.grants()[0].granted, 44.6, 6.0);
  for (std::size_t k = 1; k < 3; ++k) {
    const double gap = sim.grants()[k].granted - sim.grants()[k - 1].released;
    EXPECT_GE(gap, 40.0 - 13.0);
    EXPECT_LE(gap, 40.0 + 1.0);
  }
  EXPECT_EQ(sim.violations(), 0u);
  bool silent = false;  // 30 deferred to 11's earlier request
  for (const RobotEvent& e : sim.events()) {
    silent |= e.robot == 1 && e.event.kind == MutexEvent::Kind::kStateChange && e.event.state == State::kSilent;
  }
  EXPECT_TRUE(silent);
}

TrialOptions Teams(int min_robots, int max_robots) {
  TrialOptions trials;
  trials.min_robots = min_robots;
  trials.max_robots = max_robots;
  return trials;
}

TEST(TeamSim, ThousandNoiseFreeTrialsAreSafeAndLive) {
  auto model = OpenFloor();
  const TrialSummary s = RunTrials(*model, Teams(2, 6), {}, 1000);
  EXPECT_EQ(s.trials, 1000);
  EXPECT_EQ(s.violations, 0u);
  EXPECT_EQ(s.liveness_failures, 0u);
  EXPECT_GE(s.grants, 2000u);  // every robot of every trial got the lock
  EXPECT_GT(s.mean_wait, 40.0);
}

TEST(TeamSim, LosingEverythingBreaksSafetyAndTheMonitorSeesIt) {
  auto model = OpenFloor();
  TrialOptions trials = Teams(4, 4);
  trials.want_spread = 5.0;  // all want it at once, hold it long
  trials.hold_min = trials.hold_max = 60.0;
  TeamSimOptions options;
  options.loss = 1.0;
  const TrialSummary s = RunTrials(*model, trials, options, 5);
  EXPECT_GT(s.violations, 0u);
  EXPECT_GT(s.lost, 0u);
}

TEST(TeamSim, CorruptedPacketsDelayButStaySafe) {
  auto model = OpenFloor();
  const TrialOptions trials = Teams(3, 4);
  const TrialSummary clean = RunTrials(*model, trials, {}, 100);
  TeamSimOptions noisy;
  noisy.noise = 0.3;
  const TrialSummary s = RunTrials(*model, trials, noisy, 100);
  EXPECT_GT(s.corrupted, 0u);
  EXPECT_EQ(s.violations, 0u);
  EXPECT_EQ(s.liveness_failures, 0u);
  EXPECT_GT(s.mean_wait, clean.mean_wait);  // noise restarts grab timers but never lets two in
}

TEST(TeamSim, RefusesRobotsInWallsAndImpossibleProbabilities) {
  auto model = OpenFloor(10.0);
  try {
    TeamSim sim(*model, {{7, {50.0, 5.0}, {}}}, {});
    ADD_FAILURE() << "a robot off the map was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("robot 7"), std::string::npos) << e.what();
  }
  TeamSimOptions options;
  options.noise = 1.5;
  EXPECT_THROW(TeamSim(*model, {}, options), std::invalid_argument);
  options = {};
  options.mutex.lock_mean = 50.0;  // longer than t_grab
  EXPECT_THROW(TeamSim(*model, {{7, {5.0, 5.0}, {}}}, options), std::invalid_argument);
}

// The acoustic channel with a table that decodes `delivered` of the packets everywhere, in a
// quiet room.
TeamSimOptions Acoustic(double delivered) {
  TeamSimOptions options;
  world_sim::Acoustics acoustics;
  acoustics.room.rt60 = 0.4;
  acoustics.room.critical_distance = 2.0;
  options.acoustics = acoustics;
  options.decode_table = std::make_shared<const audio_propagation::DecodeTable>(
      audio_propagation::test::FlatTable("nava", delivered));
  return options;
}

TEST(TeamSim, OnAnAcousticChannelThatDeliversEverythingTheThreeAreServedInOrder) {
  const TeamSimOptions options = Acoustic(1.0);
  auto model = OpenFloor(20.0, options.acoustics);
  TeamSim sim(*model, ThreeScenario(Centre(*model)), options);
  sim.Run(3600.0);
  ASSERT_TRUE(sim.Done());
  ASSERT_EQ(sim.grants().size(), 3u);
  for (std::size_t k = 1; k < 3; ++k) EXPECT_TRUE(Precedes(sim.grants()[k - 1].request, sim.grants()[k].request));
  EXPECT_TRUE(sim.InRange(0, 1) && sim.InRange(1, 2) && sim.InRange(0, 2));
  EXPECT_EQ(sim.violations(), 0u);
  // They heard each other: each took the lock only once the one before had let it go.
  for (std::size_t k = 1; k < 3; ++k) EXPECT_GE(sim.grants()[k].granted, sim.grants()[k - 1].released);
}

TEST(TeamSim, RobotsWhosePacketsTheModelNeverDeliversAreOutOfRange) {
  // Nobody hears anybody: robots 11 and 30 each take the lock t_grab after wanting it, at once,
  // and that is no violation, since the lock promises nothing to robots that cannot hear each
  // other; robot 212, which waits to hear two packets, never wants it.
  const TeamSimOptions options = Acoustic(0.0);
  auto model = OpenFloor(20.0, options.acoustics);
  TeamSim sim(*model, ThreeScenario(Centre(*model)), options);
  sim.Run(3600.0);
  EXPECT_FALSE(sim.InRange(0, 1) || sim.InRange(1, 2) || sim.InRange(0, 2));
  ASSERT_EQ(sim.grants().size(), 2u);
  for (const Grant& g : sim.grants()) EXPECT_NEAR(g.granted, g.wanted + 40.0, 1.0);
  EXPECT_LT(sim.grants()[1].granted, sim.grants()[0].released);
  EXPECT_EQ(sim.violations(), 0u);
  EXPECT_EQ(sim.mutex(2).counters().heard, 0u);
}

TEST(TeamSim, TheAcousticChannelNeedsBothATableAndAcoustics) {
  auto model = OpenFloor(10.0);
  TeamSimOptions options = Acoustic(1.0);
  options.acoustics.reset();
  try {
    TeamSim sim(*model, {{7, {5.0, 5.0}, {}}}, options);
    ADD_FAILURE() << "a decode table without acoustics was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no acoustics"), std::string::npos) << e.what();
  }
  options = Acoustic(1.0);
  options.decode_table.reset();
  EXPECT_THROW(TeamSim(*model, {{7, {5.0, 5.0}, {}}}, options), std::invalid_argument);
}

TEST(Timeline, DrawsARecordedRunAndRefusesAnUnrecordedOne) {
  auto model = OpenFloor();
  const auto three = RecordedThree(*model);
  const TeamSim& sim = *three;
  const std::string path = ::testing::TempDir() + "timeline_test.png";
  DrawTimeline(sim, path);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  unsigned char magic[4] = {};
  ASSERT_EQ(std::fread(magic, 1, 4, f), 4u);
  std::fclose(f);
  EXPECT_EQ(magic[1], 'P');
  EXPECT_EQ(magic[2], 'N');
  EXPECT_THROW(DrawTimeline(sim, "/nonexistent-dir/t.png"), std::runtime_error);

  TeamSim quiet(*model, SingleScenario(Centre(*model)), {});
  quiet.Run(10.0);
  EXPECT_THROW(DrawTimeline(quiet, path), std::runtime_error);
}

TEST(TeamSim, ImpossibleOptionsAreNamed) {
  const auto message = [](const auto& check) {
    try {
      check();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NO_THROW(ValidateTeamSimOptions({}));
  EXPECT_NO_THROW(ValidateTrialOptions({}));
  TeamSimOptions sim;
  sim.step = 0.0;
  EXPECT_EQ(message([&] { ValidateTeamSimOptions(sim); }), "team sim: step = 0.000000: expected > 0 s");
  sim = {};
  sim.loss = 1.5;
  EXPECT_NE(message([&] { ValidateTeamSimOptions(sim); }).find("loss = 1.5"), std::string::npos);
  TrialOptions trials;
  trials.hold_max = 1.0;
  EXPECT_EQ(message([&] { ValidateTrialOptions(trials); }), "trials: hold_max = 1: expected at least hold_min");
  trials = {};
  trials.min_robots = 7;
  EXPECT_NE(message([&] { ValidateTrialOptions(trials); }).find("got 7..6"), std::string::npos);
}

}  // namespace
}  // namespace local_mutex
