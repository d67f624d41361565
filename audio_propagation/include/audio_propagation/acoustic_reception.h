#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/reception_model.h"

namespace audio_propagation {

// The acoustic model (acoustic_model.h): a packet reaches every robot a path reaches, at its
// direct-plus-reverberant level; the air holds the ambient sound and the noise sources sounding
// (worked out again every kBackgroundSeconds); and at the end of an arrival the decode table
// decides, by the draw, whether the robot decodes it, reports noise of some class or notices
// nothing, against the noise over the arrival and the other packets overlapping it (each
// weighted by how much it overlapped). Robots calibrate their own carrier thresholds.
class AcousticReception : public ReceptionModel {
 public:
  // Seconds between updates of the noise at each robot (it changes as robots move a cell or a
  // source turns on or off).
  static constexpr double kBackgroundSeconds = 0.05;
  // An arrival this far below the noise (dB) changes neither a carrier nor a decision.
  static constexpr double kNegligibleSnrDb = -30.0;
  // `model` must outlive this. Silence reads as `noise_floor_db` (finite, else
  // std::invalid_argument).
  AcousticReception(const AcousticModel& model, double noise_floor_db);
  std::optional<double> CarrierThresholdDb() const override { return std::nullopt; }
  double BackgroundSeconds() const override { return kBackgroundSeconds; }
  void Background(double time, const std::vector<Eigen::Vector2d>& at, std::vector<double>& powers) const override;
  double LevelDb(double power) const override;
  bool Quiet(double power, double background, double level_db, const nava_modem::CsmaMac& mac) const override;
  bool Predicts() const override { return true; }
  ArrivalSound Arrive(const SoundPath& path, std::size_t listener, const std::vector<Eigen::Vector2d>& at,
                      double time) const override;
  Decision Decide(const SoundPath& path, std::size_t listener, double level_db, double start, double end,
                  const std::vector<Overlap>& overlaps, const std::vector<Eigen::Vector2d>& at,
                  const std::function<double()>& draw) const override;
  const AcousticModel* acoustic() const override { return &model_; }

 private:
  const AcousticModel& model_;
  double noise_floor_db_;
};

}  // namespace audio_propagation
