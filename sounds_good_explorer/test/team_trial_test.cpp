#include "sounds_good_explorer/experiment.h"
#include "sounds_good_explorer/team_trial.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "grid/map_file.h"

namespace sounds_good_explorer {
namespace {

// The 6 x 4 m test room (a wall splits it, with a gap at the top): one robot in the left half,
// the source in the right half, the sink back on the left.
struct SmallWorld {
  grid::OccupancyMap map = grid::LoadMapFile(std::string(PROJECT_MAPS_DIR) + "/test_room.yaml");
  world_sim::WorldConfig config;
  audio_propagation::PropagationModel model{map, {}};
  SmallWorld() {
    config.map_file = "test_room";
    config.robots = {{"robot_0", {1.0, 1.0, 0.0}}};
    config.markers = {{1, 5.0, 1.0}, {2, 1.0, 3.0}};
  }
};

TEST(TeamTrial, OneRobotFindsBothMarkersAndCompletesJobs) {
  const SmallWorld w;
  TrialOptions o;
  o.jobs = 4;
  o.time_cap = 1500.0;
  o.explorer.task.work_time = 10.0;
  const TrialResult r = RunTeamTrial(w.map, w.config, w.model, o);
  ASSERT_FALSE(r.censored) << "only " << r.jobs.size() << " jobs by the cap";
  ASSERT_EQ(r.jobs.size(), 4u);
  for (std::size_t j = 0; j < r.jobs.size(); ++j) {
    EXPECT_EQ(r.jobs[j].marker, j % 2 == 0 ? 1u : 2u);  // source, sink, source, sink
    EXPECT_EQ(r.jobs[j].robot, 0u);
    if (j > 0) {
      EXPECT_GE(r.jobs[j].time - r.jobs[j - 1].time, 10.0);  // the work takes 10 s
    }
  }
  EXPECT_DOUBLE_EQ(r.time, r.jobs.back().time);
  EXPECT_GT(r.packets_sent, 0u);  // it announced what it saw
}

TEST(TeamTrial, AnUnfinishedTrialIsCensoredAtTheCap) {
  const SmallWorld w;
  TrialOptions o;
  o.jobs = 50;
  o.time_cap = 60.0;
  const TrialResult r = RunTeamTrial(w.map, w.config, w.model, o);
  EXPECT_TRUE(r.censored);
  EXPECT_DOUBLE_EQ(r.time, 60.0);
  EXPECT_LT(r.jobs.size(), 50u);
}

TEST(TeamTrial, SameSeedSameTrial) {
  const SmallWorld w;
  TrialOptions o;
  o.jobs = 2;
  o.time_cap = 600.0;
  o.seed = 9;
  const TrialResult a = RunTeamTrial(w.map, w.config, w.model, o);
  const TrialResult b = RunTeamTrial(w.map, w.config, w.model, o);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.jobs.size(), b.jobs.size());
}

TEST(TeamTrial, ExperimentRowsDoNotDependOnTheThreadCount) {
  const SmallWorld w;
  ExperimentOptions o;
  o.modes = {ListenMode::kNone, ListenMode::kOmni};
  o.trials = 2;
  o.trial.jobs = 2;
  o.trial.time_cap = 600.0;
  o.threads = 1;
  const std::vector<TrialRow> one = RunExperiment(w.map, {w.config}, w.model, o);
  o.threads = 3;
  const std::vector<TrialRow> three = RunExperiment(w.map, {w.config}, w.model, o);
  ASSERT_EQ(one.size(), 4u);
  ASSERT_EQ(three.size(), 4u);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].mode, three[i].mode);
    EXPECT_EQ(one[i].seed, three[i].seed);
    EXPECT_EQ(one[i].result.time, three[i].result.time) << i;
  }
}

TEST(TeamTrial, ImpossibleRequestsAreRefused) {
  const SmallWorld w;
  TrialOptions o;
  o.jobs = 0;
  EXPECT_THROW(RunTeamTrial(w.map, w.config, w.model, o), std::invalid_argument);
  o = TrialOptions();
  world_sim::WorldConfig empty = w.config;
  empty.robots.clear();
  EXPECT_THROW(RunTeamTrial(w.map, empty, w.model, o), std::invalid_argument);
  o.explorer.task.sink = o.explorer.task.source;
  EXPECT_THROW(RunTeamTrial(w.map, w.config, w.model, o), std::invalid_argument);
}

TEST(Experiment, ImpossibleOptionsAreNamed) {
  EXPECT_NO_THROW(ValidateOptions(ExperimentOptions{}));
  ExperimentOptions o;
  o.threads = -1;
  try {
    ExperimentRows(1, o);
    ADD_FAILURE() << "a negative thread count was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "threads must be at least 0 (0: one per core), got -1");
  }
  o = {};
  o.modes.clear();
  EXPECT_THROW(ExperimentRows(1, o), std::invalid_argument);
  o = {};
  o.trial.jobs = 0;
  EXPECT_THROW(ValidateOptions(o), std::invalid_argument);
}

}  // namespace
}  // namespace sounds_good_explorer
