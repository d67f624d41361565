#include "audio_propagation/microphone.h"

#include <cmath>
#include <limits>

#include "grid/pose2d.h"

namespace audio_propagation {

double SenseDirection(world_sim::Microphone microphone, double arrival_world, double robot_yaw,
                      double noise_std, std::mt19937& rng) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (std::isnan(arrival_world)) return kNaN;
  const double relative = grid::NormalizeAngle(arrival_world - robot_yaw);
  switch (microphone) {
    case world_sim::Microphone::kOmni: {
      if (noise_std <= 0.0) return relative;
      std::normal_distribution<double> noise(0.0, noise_std);
      return grid::NormalizeAngle(relative + noise(rng));
    }
    case world_sim::Microphone::kBidirectional:
      return std::abs(relative) <= M_PI / 2 ? 0.0 : M_PI;
    case world_sim::Microphone::kNone:
      return kNaN;
  }
  return kNaN;
}

SensedDirection SenseDirection(world_sim::Microphone microphone, double arrival_world, double robot_yaw,
                               const DirectionErrors& errors, double drr_db, double rt60, std::mt19937& rng) {
  if (std::isnan(arrival_world)) return {std::numeric_limits<double>::quiet_NaN(), 0.0};
  return errors.Sense(microphone, grid::NormalizeAngle(arrival_world - robot_yaw), drr_db, rt60, rng);
}

}  // namespace audio_propagation
