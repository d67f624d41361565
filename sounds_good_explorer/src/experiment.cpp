#include "sounds_good_explorer/experiment.h"

#include <stdexcept>
#include <string>

#include "tool_args/parallel_for.h"

namespace sounds_good_explorer {

std::uint32_t TrialSeed(std::uint32_t base, int config, int trial) {
  return base * 1000003u + static_cast<std::uint32_t>(config) * 1009u +
         static_cast<std::uint32_t>(trial);
}

std::vector<TrialRow> RunExperiment(const grid::OccupancyMap& map,
                                    const std::vector<world_sim::WorldConfig>& configs,
                                    const audio_propagation::PropagationModel& model,
                                    const ExperimentOptions& options,
                                    const std::function<void(int, int)>& progress) {
  if (options.trials < 1)
    throw std::invalid_argument("trials must be at least 1, got " + std::to_string(options.trials));
  if (options.modes.empty()) throw std::invalid_argument("at least one mode is needed");
  ValidateOptions(options.trial);
  std::vector<TrialRow> rows;
  for (std::size_t c = 0; c < configs.size(); ++c)
    for (ListenMode mode : options.modes)
      for (int t = 1; t <= options.trials; ++t) {
        TrialRow row;
        row.config = static_cast<int>(c) + 1;
        row.mode = mode;
        row.trial = t;
        row.seed = TrialSeed(options.seed, row.config, t);
        rows.push_back(row);
      }

  multirobot_audio::tools::ParallelFor(
      rows.size(), options.threads,
      [&](std::size_t i) {
        TrialRow& row = rows[i];
        TrialOptions o = options.trial;
        o.mode = row.mode;
        o.seed = row.seed;
        row.result = RunTeamTrial(map, configs[row.config - 1], model, o);
      },
      progress);
  return rows;
}

}  // namespace sounds_good_explorer
