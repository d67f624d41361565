#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "local_navigation/local_map.h"
#include "sounds_good_explorer/heard_messages.h"

namespace sounds_good_explorer {

struct FrontierOptions {
  double noise_std = 0.3;     // m: the small Gaussian term G that breaks ties and loops
  double audio_weight = 3.0;  // m: w, what a fresh, loud, agreeing message is worth in distance
  // Frontiers nearer than this are skipped: with eight narrow rangers nearly every free cell
  // next to the robot borders unknown, and chasing those would hold the robot in place.
  double min_distance = 1.0;  // m
};

void ValidateOptions(const FrontierOptions& options);

// The frontier cost f(c, M) = |c| + G - w * score(c, M) (see HeardMessages), |c| the Euclidean
// distance from the robot in metres. Returns the frontier with the least cost among those at
// least min_distance away (or, when there are none, among all), nullopt when there are no
// frontiers. `excluded` cells are skipped (goals found unreachable).
std::optional<Eigen::Vector2i> ChooseFrontier(const local_navigation::LocalMap& map,
                                              const std::vector<Eigen::Vector2i>& frontiers,
                                              const Eigen::Vector2d& robot,
                                              const HeardMessages& heard, std::uint32_t marker,
                                              double time, const FrontierOptions& options,
                                              std::mt19937& rng,
                                              const std::vector<Eigen::Vector2i>& excluded = {});

}  // namespace sounds_good_explorer
