#pragma once

// A peak found between samples: the vertex of the parabola through a sampled maximum and its two
// neighbours (chirp positions, array lags and bearings, a survey's alignments). No ROS.
#include <algorithm>

namespace nava_modem {

// The peak's offset from the middle point of a parabola through (-1, a), (0, b), (1, c), within
// half a sample; 0 where the three do not bend down (no maximum between them).
inline double ParabolaOffset(double a, double b, double c) {
  const double curvature = a - 2.0 * b + c;
  if (curvature >= 0.0) return 0.0;
  return std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
}

}  // namespace nava_modem
