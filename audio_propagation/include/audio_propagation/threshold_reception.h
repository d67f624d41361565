#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "audio_propagation/reception_model.h"

namespace audio_propagation {

// The thesis's model: a packet is heard wherever its path is audible (above the hearing
// threshold), at the path's level, in silent air; it arrives whole unless another audible
// transmission overlapped it at that robot and was not weaker by the capture margin, and then as
// noise (a collision). The carrier threshold is the hearing threshold.
class ThresholdReception : public ReceptionModel {
 public:
  // Levels below `noise_floor_db` read as it. Throws std::invalid_argument for a capture margin
  // below 0 or a level that is not finite.
  ThresholdReception(double threshold_db, double capture_margin_db, double noise_floor_db);
  std::optional<double> CarrierThresholdDb() const override { return threshold_db_; }
  double BackgroundSeconds() const override { return 0.0; }
  void Background(double, const std::vector<Eigen::Vector2d>&, std::vector<double>& powers) const override;
  double LevelDb(double power) const override;
  bool Quiet(double power, double background, double level_db, const nava_modem::CsmaMac& mac) const override;
  bool Predicts() const override { return false; }
  ArrivalSound Arrive(const SoundPath& path, std::size_t listener, const std::vector<Eigen::Vector2d>& at,
                      double time) const override;
  Decision Decide(const SoundPath& path, std::size_t listener, double level_db, double start, double end,
                  const std::vector<Overlap>& overlaps, const std::vector<Eigen::Vector2d>& at,
                  const std::function<double()>& draw) const override;

 private:
  double threshold_db_, capture_margin_db_, noise_floor_db_;
};

}  // namespace audio_propagation
