#pragma once

// Where a robot would be heard: the acoustic model's decode probability from one sender to every
// free cell of a coarse grid over the map, for a heat map in rviz or a plot. No ROS.
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/acoustic_model.h"

namespace audio_propagation {

struct DeliveryMap {
  int width = 0, height = 0;  // cells
  double resolution = 0.0;    // m per cell
  Eigen::Vector2d origin{0.0, 0.0};  // world position of cell (0, 0)'s corner
  // Row-major from the origin, the chance a listener at the cell's centre decodes a packet from
  // the sender; NaN where the centre is not free space or no path reaches it.
  std::vector<double> probability;
};

// The map for a sender at `from` at time `t`, the robots at `robots` (their motors may be noise
// sources), on cells of `resolution` m (at least the map's own). Throws std::invalid_argument
// for a resolution <= 0.
DeliveryMap MapDelivery(const AcousticModel& model, const Eigen::Vector2d& from, double t,
                        const std::vector<Eigen::Vector2d>& robots, double resolution);

}  // namespace audio_propagation
