#include "sounds_good_explorer/frontier_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "grid/option_checks.h"

namespace sounds_good_explorer {

using grid::RequireAtLeast;

void ValidateOptions(const FrontierOptions& o) {
  RequireAtLeast("frontier noise_std (m)", o.noise_std, 0.0);
  RequireAtLeast("frontier audio_weight (m)", o.audio_weight, 0.0);
  RequireAtLeast("frontier min_distance (m)", o.min_distance, 0.0);
}

std::optional<Eigen::Vector2i> ChooseFrontier(const local_navigation::LocalMap& map,
                                              const std::vector<Eigen::Vector2i>& frontiers,
                                              const Eigen::Vector2d& robot,
                                              const HeardMessages& heard, std::uint32_t marker,
                                              double time, const FrontierOptions& options,
                                              std::mt19937& rng,
                                              const std::vector<Eigen::Vector2i>& excluded) {
  std::normal_distribution<double> gaussian(0.0, 1.0);
  const bool listen = options.audio_weight > 0.0 && heard.Has(marker);
  std::optional<Eigen::Vector2i> best, best_near;
  double best_cost = std::numeric_limits<double>::infinity(), best_near_cost = best_cost;
  for (const Eigen::Vector2i& cell : frontiers) {
    if (std::find(excluded.begin(), excluded.end(), cell) != excluded.end()) continue;
    const Eigen::Vector2d offset = map.CentreOf(cell) - robot;
    const double distance = offset.norm();
    double cost = distance + options.noise_std * gaussian(rng);
    if (listen)
      cost -= options.audio_weight *
              heard.Score(marker, std::atan2(offset.y(), offset.x()), time);
    if (distance >= options.min_distance) {
      if (cost < best_cost) best_cost = cost, best = cell;
    } else if (cost < best_near_cost) {
      best_near_cost = cost, best_near = cell;
    }
  }
  return best ? best : best_near;
}

}  // namespace sounds_good_explorer
