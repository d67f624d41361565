#include "sounds_good_explorer/experiment.h"

#include <stdexcept>
#include <string>

#include "tool_args/parallel_for.h"

namespace sounds_good_explorer {

std::uint32_t TrialSeed(std::uint32_t base, int config, int trial) {
  return base * 1000003u + static_cast<std::uint32_t>(config) * 1009u +
         static_cast<std::uint32_t>(trial);
}

void ValidateOptions(const ExperimentOptions& o) {
  if (o.modes.empty()) throw std::invalid_argument("modes: at least one mode is needed, got none");
  if (o.trials < 1) throw std::invalid_argument("trials must be at least 1, got " + std::to_string(o.trials));
  if (o.threads < 0)
    throw std::invalid_argument("threads must be at least 0 (0: one per core), got " + std::to_string(o.threads));
  ValidateOptions(o.trial);
}

std::vector<TrialRow> ExperimentRows(int configs, const ExperimentOptions& options) {
  ValidateOptions(options);
  std::vector<TrialRow> rows;
  for (int c = 1; c <= configs; ++c)
    for (ListenMode mode : options.modes)
      for (int t = 1; t <= options.trials; ++t) {
        TrialRow row;
        row.config = c;
        row.mode = mode;
        row.trial = t;
        row.seed = TrialSeed(options.seed, row.config, t);
        rows.push_back(row);
      }
  return rows;
}

void RunRows(const grid::OccupancyMap& map, const std::vector<world_sim::WorldConfig>& configs,
             const audio_propagation::PropagationModel& model, const ExperimentOptions& options,
             const std::vector<std::size_t>& which, std::vector<TrialRow>& rows,
             const std::function<void(int, int)>& progress) {
  ValidateOptions(options);
  multirobot_audio::tools::ParallelFor(
      which.size(), options.threads,
      [&](std::size_t k) {
        TrialRow& row = rows.at(which[k]);
        TrialOptions o = options.trial;
        o.mode = row.mode;
        o.seed = row.seed;
        row.result = RunTeamTrial(map, configs.at(row.config - 1), model, o);
      },
      progress);
}

std::vector<TrialRow> RunExperiment(const grid::OccupancyMap& map,
                                    const std::vector<world_sim::WorldConfig>& configs,
                                    const audio_propagation::PropagationModel& model,
                                    const ExperimentOptions& options,
                                    const std::function<void(int, int)>& progress) {
  std::vector<TrialRow> rows = ExperimentRows(static_cast<int>(configs.size()), options);
  std::vector<std::size_t> all(rows.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  RunRows(map, configs, model, options, all, rows, progress);
  return rows;
}

}  // namespace sounds_good_explorer
