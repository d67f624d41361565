#pragma once

// Impulse responses whose RT60 and DRR are known by construction, for the tests of what reads
// them (measured_response_test, response_survey_test).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace nava_modem {

// A response with its direct sound (1) at `delay` samples and, from 5 ms after it, white noise
// decaying by 60 dB in `rt60` seconds, scaled so that the direct sound's energy over the rest is
// `drr_db` (the same in every band: both are white). With `late_rt60`, the tail's decay slows
// as a hall's often does: a second, slower decay `late_db` under the first where both begin.
inline std::vector<float> KnownResponse(double rt60, double drr_db, double rate, std::size_t delay, unsigned seed,
                                        double late_rt60 = 0.0, double late_db = 0.0) {
  const double longest = std::max(rt60, late_rt60);
  const double late = late_rt60 > 0.0 ? std::pow(10.0, late_db / 20.0) : 0.0;
  std::vector<float> h(delay + static_cast<std::size_t>(1.5 * longest * rate), 0.0f);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> tail(h.size(), 0.0);
  double energy = 0.0;
  for (std::size_t k = delay + static_cast<std::size_t>(0.005 * rate); k < h.size(); ++k) {
    const double t = static_cast<double>(k - delay) / rate;
    const double envelope = std::exp(-6.907755 * t / rt60) + (late > 0.0 ? late * std::exp(-6.907755 * t / late_rt60) : 0.0);
    tail[k] = gauss(rng) * envelope;
    energy += tail[k] * tail[k];
  }
  const double scale = std::sqrt(std::pow(10.0, -drr_db / 10.0) / energy);
  for (std::size_t k = 0; k < h.size(); ++k) h[k] = static_cast<float>(scale * tail[k]);
  h[delay] = 1.0f;
  return h;
}

}  // namespace nava_modem
