#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "audio_propagation/propagation_model.h"
#include "grid/occupancy_map.h"
#include "sounds_good_explorer/team_trial.h"
#include "world_sim/world_config.h"

namespace sounds_good_explorer {

struct ExperimentOptions {
  std::vector<ListenMode> modes{ListenMode::kNone, ListenMode::kBidirectional, ListenMode::kOmni};
  int trials = 20;          // per configuration and mode
  TrialOptions trial;       // mode and seed are set per trial
  int threads = 0;          // 0: one per core
  std::uint32_t seed = 1;
};

// Throws std::invalid_argument naming the field, its value and what was expected: no mode,
// trials under 1, a negative thread count, impossible trial options.
void ValidateOptions(const ExperimentOptions& options);

struct TrialRow {
  int config = 0;  // 1-based, as the thesis numbers them
  ListenMode mode = ListenMode::kNone;
  int trial = 0;   // 1-based
  std::uint32_t seed = 0;
  TrialResult result;
};

// The seed of one trial: the same for every mode, so the modes meet the same odometry noise and
// controller draws where their runs agree.
std::uint32_t TrialSeed(std::uint32_t base, int config, int trial);

// Every configuration x mode x trial of an experiment on `configs` configurations, with its
// seed and no result yet, in (config, mode, trial) order: the order of a whole run, which
// numbers the trials for shards. Throws std::invalid_argument for impossible options.
std::vector<TrialRow> ExperimentRows(int configs, const ExperimentOptions& options);

// Runs rows[i] for every i in `which` (a shard's share, or all), spread over `threads` worker
// threads; `progress` counts them as RunExperiment does.
void RunRows(const grid::OccupancyMap& map, const std::vector<world_sim::WorldConfig>& configs,
             const audio_propagation::PropagationModel& model, const ExperimentOptions& options,
             const std::vector<std::size_t>& which, std::vector<TrialRow>& rows,
             const std::function<void(int, int)>& progress = {});

// Runs every configuration x mode x trial, spread over `threads` worker threads (each trial is
// independent and deterministic, so the rows do not depend on the thread count). `progress`
// is called after each trial with (done, total), from one thread at a time. Rows come back in
// (config, mode, trial) order.
std::vector<TrialRow> RunExperiment(const grid::OccupancyMap& map,
                                    const std::vector<world_sim::WorldConfig>& configs,
                                    const audio_propagation::PropagationModel& model,
                                    const ExperimentOptions& options,
                                    const std::function<void(int, int)>& progress = {});

}  // namespace sounds_good_explorer
