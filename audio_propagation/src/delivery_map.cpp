#include "audio_propagation/delivery_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace audio_propagation {

DeliveryMap MapDelivery(const AcousticModel& model, const Eigen::Vector2d& from, double t,
                        const std::vector<Eigen::Vector2d>& robots, double resolution) {
  if (!(resolution > 0.0)) {
    throw std::invalid_argument("delivery map: resolution must be above 0 m, got " + std::to_string(resolution));
  }
  const grid::OccupancyMap& map = model.propagation().map();
  DeliveryMap out;
  out.resolution = std::max(resolution, map.resolution());
  out.width = std::max(1, static_cast<int>(std::floor(map.width_m() / out.resolution)));
  out.height = std::max(1, static_cast<int>(std::floor(map.height_m() / out.resolution)));
  out.origin = map.CellCoordsToWorld({0.0, 0.0});
  out.probability.assign(static_cast<std::size_t>(out.width) * out.height, std::numeric_limits<double>::quiet_NaN());

  std::vector<Eigen::Vector2d> centres;
  std::vector<std::size_t> index;
  for (int j = 0; j < out.height; ++j) {
    for (int i = 0; i < out.width; ++i) {
      const Eigen::Vector2d c = out.origin + Eigen::Vector2d(i + 0.5, j + 0.5) * out.resolution;
      if (!map.IsFreeAt(c)) continue;
      centres.push_back(c);
      index.push_back(static_cast<std::size_t>(j) * out.width + i);
    }
  }
  const std::vector<SoundPath> paths = model.propagation().From(from, centres);
  for (std::size_t k = 0; k < centres.size(); ++k) {
    if (!paths[k].reachable) continue;
    out.probability[index[k]] = model.Predict(paths[k], centres[k], model.NoiseAt(centres[k], t, robots)).probability;
  }
  return out;
}

}  // namespace audio_propagation
