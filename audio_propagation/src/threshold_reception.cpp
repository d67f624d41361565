#include "audio_propagation/threshold_reception.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "grid/option_checks.h"

namespace audio_propagation {

ThresholdReception::ThresholdReception(double threshold_db, double capture_margin_db, double noise_floor_db)
    : threshold_db_(threshold_db), capture_margin_db_(capture_margin_db), noise_floor_db_(noise_floor_db) {
  grid::RequireAtLeast("threshold reception capture_margin_db (dB)", capture_margin_db, 0.0);
  if (!std::isfinite(threshold_db) || !std::isfinite(noise_floor_db)) {
    throw std::invalid_argument("threshold reception: expected finite levels, got threshold_db " + std::to_string(threshold_db) +
                                " and noise_floor_db " + std::to_string(noise_floor_db));
  }
}

void ThresholdReception::Background(double, const std::vector<Eigen::Vector2d>& at, std::vector<double>& powers) const {
  powers.assign(at.size(), 0.0);
}

double ThresholdReception::LevelDb(double power) const {
  if (!(power > 0.0)) return noise_floor_db_;
  return std::max(noise_floor_db_, 10.0 * std::log10(power));
}

bool ThresholdReception::Quiet(double, double, double level_db, const nava_modem::CsmaMac&) const {
  return level_db == noise_floor_db_;
}

ArrivalSound ThresholdReception::Arrive(const SoundPath& path, std::size_t, const std::vector<Eigen::Vector2d>&, double) const {
  ArrivalSound sound;
  if (path.audible) sound.level_db = path.level_db;
  return sound;
}

Decision ThresholdReception::Decide(const SoundPath&, std::size_t, double level_db, double, double,
                                    const std::vector<Overlap>& overlaps, const std::vector<Eigen::Vector2d>&,
                                    const std::function<double()>&) const {
  double loudest_other = -std::numeric_limits<double>::infinity();
  for (const Overlap& o : overlaps) loudest_other = std::max(loudest_other, o.level_db);
  Decision d;
  d.packet = level_db >= loudest_other + capture_margin_db_;
  d.collision = !d.packet;
  return d;
}

}  // namespace audio_propagation
