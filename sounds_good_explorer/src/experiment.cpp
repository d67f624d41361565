#include "sounds_good_explorer/experiment.h"

#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

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

  int threads = options.threads > 0 ? options.threads
                                    : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(1, std::min<int>(threads, static_cast<int>(rows.size())));
  std::atomic<std::size_t> next{0};
  std::mutex lock;
  int done = 0;
  std::exception_ptr failure;
  auto work = [&]() {
    for (std::size_t i = next++; i < rows.size(); i = next++) {
      TrialRow& row = rows[i];
      TrialOptions o = options.trial;
      o.mode = row.mode;
      o.seed = row.seed;
      try {
        row.result = RunTeamTrial(map, configs[row.config - 1], model, o);
      } catch (...) {
        std::lock_guard<std::mutex> guard(lock);
        if (!failure) failure = std::current_exception();
        next = rows.size();
        return;
      }
      std::lock_guard<std::mutex> guard(lock);
      ++done;
      if (progress) progress(done, static_cast<int>(rows.size()));
    }
  };
  std::vector<std::thread> pool;
  for (int k = 0; k < threads; ++k) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return rows;
}

}  // namespace sounds_good_explorer
