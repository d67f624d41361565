#include "audio_propagation/acoustic_reception.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace audio_propagation {

AcousticReception::AcousticReception(const AcousticModel& model, double noise_floor_db)
    : model_(model), noise_floor_db_(noise_floor_db) {
  if (!std::isfinite(noise_floor_db)) {
    throw std::invalid_argument("acoustic reception noise_floor_db must be a finite level in dB, got " +
                                std::to_string(noise_floor_db));
  }
}

void AcousticReception::Background(double time, const std::vector<Eigen::Vector2d>& at, std::vector<double>& powers) const {
  model_.PreparePaths(at, at);
  powers.assign(at.size(), 0.0);
  for (std::size_t r = 0; r < at.size(); ++r) {
    double power = 0.0;
    // What the robot's level meter reads: each noise by its share in the profile's bands.
    for (const Disturbance& d : model_.NoiseAt(at[r], time, at)) power += d.power * d.heard;
    powers[r] = power;
  }
}

double AcousticReception::LevelDb(double power) const {
  return power > 0.0 ? 10.0 * std::log10(power) : noise_floor_db_;
}

bool AcousticReception::Quiet(double power, double background, double level_db, const nava_modem::CsmaMac& mac) const {
  // The noise is always there: quiet while it stays below the carrier threshold.
  return power == background && !mac.carrier() && level_db < mac.threshold_db();
}

ArrivalSound AcousticReception::Arrive(const SoundPath& path, std::size_t listener, const std::vector<Eigen::Vector2d>& at,
                                       double time) const {
  ArrivalSound sound;
  if (!path.reachable) return sound;
  const LinkPrediction p = model_.Predict(path, at[listener], model_.NoiseAt(at[listener], time, at));
  sound.probability = p.probability;
  if (p.snr_db >= kNegligibleSnrDb) sound.level_db = p.signal.total_db;
  return sound;
}

Decision AcousticReception::Decide(const SoundPath& path, std::size_t listener, double, double start, double end,
                                   const std::vector<Overlap>& overlaps, const std::vector<Eigen::Vector2d>& at,
                                   const std::function<double()>& draw) const {
  // The noise over the whole arrival (its mean power, as the tables define SNR), not at one moment.
  std::vector<Disturbance> disturbances = model_.NoiseDuring(at[listener], start, end, at);
  for (const Overlap& o : overlaps) disturbances.push_back({Interference::kPacket, o.mean_power, 0.0});
  const LinkPrediction p = model_.Predict(path, at[listener], disturbances);
  Decision d;
  d.probability = p.probability;
  d.collision = p.kind == Interference::kPacket;
  const DecodeOutcome& o = p.outcome;
  const double u = draw();
  using Noise = nava_modem::RxEvent::Noise;
  if (u < o.packet) {
    d.packet = true;
  } else if (u < o.packet + o.zero_byte) {
    d.noise = Noise::kZeroByte;
  } else if (u < o.packet + o.zero_byte + o.one_byte) {
    d.noise = Noise::kOneByte;
  } else if (u < o.packet + o.zero_byte + o.one_byte + o.bad_crc) {
    d.noise = Noise::kBadCrc;
  } else {
    d.heard = false;  // the receiver would not have noticed it
  }
  return d;
}

}  // namespace audio_propagation
