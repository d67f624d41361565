#pragma once

// The `acoustic` channel model: whether a simulated robot would decode a packet, from what a
// real microphone at its place would hear. For each link it takes the shortest path around walls
// (propagation_model.h) and works out
//   direct level       L_src - 20 log10(d / d0) - corner_loss_db x corners on the path;
//   reverberant level  L_src - 20 log10(r_c / d0) - 0.174 d / RT60  (the diffuse field, equal to
//                      the free-field level at the critical distance r_c of the listener's room,
//                      falling slowly along the path as in Barron's revised theory: energy
//                      reflected late has travelled further), so the direct-to-reverberant ratio
//                      falls with distance as in a real room;
//   noise              the ambient level plus every noise source sounding at that moment (each
//                      through its own path: direct and reverberant), plus other packets in the
//                      air, as the receiver's disturbance;
// and looks the decode probability, and the noise classes of a failure, up in the profile's
// decode table (decode_table.h) by SNR, DRR, RT60 and the loudest disturbance's kind (below the
// table's lowest SNR, whatever it still decodes fades out over 10 dB).
// No ROS. The scene renderer (scene_render.h) uses the same levels to make the waveforms the
// model is validated against.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/decode_table.h"
#include "audio_propagation/propagation_model.h"
#include "audio_propagation/room_coupling.h"
#include "world_sim/acoustics.h"
#include "world_sim/world_config.h"

namespace nava_modem {
class RecordingWeight;  // nava_modem/recorded_noise.h
}

namespace audio_propagation {

// The levels of one source heard at one place.
struct LinkLevels {
  double direct_db = 0.0;
  double reverberant_db = 0.0;
  double total_db = 0.0;  // direct and reverberant power summed
  double drr_db = 0.0;
  double rt60 = 0.0;      // s, of the listener's room
};
// Pure: a source of `source_db` at `d0` m heard over a path of `length` m round `corners`
// corners, in `room` (its critical distance sets the reverberant field, its RT60 the field's fall
// along the path), the reverberant field moved by `coupling_db` (RoomCoupling: the field reaching
// another room or zone through its doorways and cross-sections; 0 in a building of one field).
// Barron's fall along the path (`barron`) is a room's own: from one zone to another the coupling
// is the fall.
LinkLevels LinkBudget(double source_db, double d0, double length, int corners, double corner_loss_db,
                      const world_sim::RoomAcoustics& room, double coupling_db = 0.0, bool barron = true);
// Pure: the critical distance (m) of a room of `rt60` s in which a listener `distance` m from a
// speaker (a straight path) hears the direct-to-reverberant ratio `drr_db`: LinkBudget inverted,
// so that a surveyed room (nava_survey) gives back its DRR in the model.
double CriticalDistanceFromDrr(double drr_db, double distance, double rt60);

// What the table says of a packet heard at `snr_db` against a disturbance of `kind`, through a
// room of `drr_db` and `rt60` s. Below the table's quietest SNR its figures fade out over
// kFadeBelowTableDb, as a receiver's do.
constexpr double kFadeBelowTableDb = 10.0;
DecodeOutcome PredictOutcome(const DecodeTable& table, Interference kind, double snr_db, double drr_db, double rt60);
// The mean outcome over packets heard at `snrs_db` each (a recorded noise's packet places,
// nava_modem::RecordingWeight::TableSnrsDb). Throws std::invalid_argument for no SNR.
DecodeOutcome PredictOutcome(const DecodeTable& table, Interference kind, const std::vector<double>& snrs_db,
                             double drr_db, double rt60);

// The quietest direct level worth a path with the acoustic model (propagation threshold_db):
// 30 dB under the ambient noise, so that the model, not the threshold, judges every link a
// receiver could decode (the room profile still decodes some 25 dB under the noise).
double AcousticThresholdDb(const world_sim::Acoustics& acoustics);
// `options` as the acoustic model judges under: paths down to AcousticThresholdDb (or the
// threshold already set, if lower) and, unless `keep_range`, no hearing range.
void UseAcousticPropagation(PropagationOptions& options, const world_sim::Acoustics& acoustics,
                            bool keep_range = false);

// One disturbance at a listener: its kind and power (linear, 10^(dB / 10)).
struct Disturbance {
  Interference kind = Interference::kPink;
  double power = 0.0;
  double frequency = 0.0;  // Hz, a whine's fundamental
  // A recorded noise (kind white): its power where the profile's receiver listens over white
  // noise's of the same power (nava_modem/recorded_noise.h), so that it counts as that much white
  // noise. 1 for every other disturbance.
  double listened = 1.0;
  // The share of its power in the profile's listening bands (carrier_share.h): what a robot's
  // carrier sense hears of it.
  double heard = 1.0;
  // A recorded noise's weighing over the receiver's cells (RecordingWeight::TableSnrsDb), owned by
  // the model; null for every other disturbance.
  const nava_modem::RecordingWeight* recording = nullptr;
};

struct LinkPrediction {
  double path_length = 0.0;  // m
  int corners = 0;
  LinkLevels signal;
  double noise_db = 0.0;     // every disturbance, as the receiver weighs it
  double snr_db = 0.0;
  Interference kind = Interference::kPink;  // the loudest disturbance
  DecodeOutcome outcome;     // from the table
  double probability = 0.0;  // outcome.packet
};

class AcousticModel {
 public:
  // Throws std::invalid_argument naming the source or field when a noise source is outside the
  // map's free space or rides on a robot not in `robot_names`, a recorded one's file is no
  // recording (unreadable, too short, silent), for impossible acoustics (RT60 <= 0,
  // no volume nor critical distance, a negative corner loss) or an empty table. Not thread-safe
  // (it keeps the paths of noise sources).
  AcousticModel(const PropagationModel& propagation, world_sim::Acoustics acoustics, DecodeTable table,
                std::vector<std::string> robot_names);

  // The ambient sound and the noise sources a listener at `at` hears at time `t`; robot-borne
  // sources are where their robot is (`robots`, indexed as robot_names). A robot hears its own
  // motors at their 1 m level.
  std::vector<Disturbance> NoiseAt(const Eigen::Vector2d& at, double t,
                                   const std::vector<Eigen::Vector2d>& robots) const;

  // The same over a packet heard from `t0` to `t1`: each noise source's power weighted by the
  // fraction of that time it sounds, so that the noise is the mean power over the packet, as the
  // decode tables define it (decode_table.h), also when a source switches on or off mid-packet.
  std::vector<Disturbance> NoiseDuring(const Eigen::Vector2d& at, double t0, double t1,
                                       const std::vector<Eigen::Vector2d>& robots) const;

  // The level (dB) at which noise source `k` (of acoustics().noise_sources) is heard at `at`
  // while it sounds, robots placed as for NoiseAt: direct and reverberant through its own path, or
  // its 1 m level when it rides on the listening robot. Nothing when no path reaches `at` or its
  // robot is not in `robots`. NoiseAt is these, for the sources sounding at `t`, and the ambient.
  std::optional<double> SourceLevelDb(std::size_t k, const Eigen::Vector2d& at,
                                      const std::vector<Eigen::Vector2d>& robots) const;

  // The levels of a packet arriving along `path` (from its first point) at `listener`.
  LinkLevels Levels(const SoundPath& path, const Eigen::Vector2d& listener) const;

  // The building's rooms when the world asks for coupled rooms (acoustics.rooms), else null.
  const RoomCoupling* rooms() const { return rooms_.get(); }

  // Finds, in one search per noise source, the paths from every source to every listener at
  // `listeners` that are not kept yet, so that the NoiseAt calls for those listeners that follow
  // cost lookups (what a channel step does for its whole team).
  void PreparePaths(const std::vector<Eigen::Vector2d>& listeners, const std::vector<Eigen::Vector2d>& robots) const;

  // The prediction for a packet along `path`, heard at `listener` against `disturbances` (from
  // NoiseAt, plus a kPacket disturbance for each overlapping packet, its power weighted by the
  // overlapping fraction).
  LinkPrediction Predict(const SoundPath& path, const Eigen::Vector2d& listener,
                         const std::vector<Disturbance>& disturbances) const;

  // The power a disturbance counts for with this profile, relative to the table's whine for a
  // whine: by the table's measured whine harm curve where it has one (nava's), else by how much
  // of its power falls in the profile's band and how close its harmonics come to the tones (a
  // rule of thumb); a recording by its `listened` weight.
  double EffectivePower(const Disturbance& d) const;

  const world_sim::Acoustics& acoustics() const { return acoustics_; }
  const DecodeTable& table() const { return table_; }
  const PropagationModel& propagation() const { return propagation_; }

 private:
  const PropagationModel& propagation_;
  world_sim::Acoustics acoustics_;
  std::unique_ptr<const RoomCoupling> rooms_;
  DecodeTable table_;
  std::vector<std::string> robot_names_;
  std::vector<int> source_robot_;  // per noise source: robot index, or -1 when fixed
  std::vector<double> source_listened_;  // per noise source: Disturbance::listened
  std::vector<double> source_heard_;     // per noise source: Disturbance::heard
  double whine_settle_s_ = 0.0;          // nava_modem::WhineSettleSeconds of the table's profile
  std::vector<std::shared_ptr<const nava_modem::RecordingWeight>> source_recording_;  // null but for recordings
  double ambient_heard_ = 1.0;           // the ambient noise's Disturbance::heard
  std::vector<double> tones_;      // Hz, a profile's few tones (nava); empty when they fill the band
  // The room whose field a listener at `at` hears from a source at `from` (the listener's RT60,
  // the source room's critical distance) and how much of that field comes through the doorways
  // between them (dB, 0 without rooms).
  struct Field {
    world_sim::RoomAcoustics room;
    double coupling_db = 0.0;
    bool barron = true;  // the listener is in the source's field (one field, or the same zone)
  };
  Field FieldBetween(const Eigen::Vector2d& from, const Eigen::Vector2d& at) const;
  // The path from noise source `source` at `from` to `to`.
  SoundPath PathBetween(std::size_t source, const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;
  std::optional<Eigen::Vector2d> SourcePosition(std::size_t k, const std::vector<Eigen::Vector2d>& robots) const;
  std::uint64_t PathKey(std::size_t source, const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;
  void Keep(std::uint64_t key, SoundPath path) const;
  static constexpr std::size_t kMaxKeptPaths = 200000;
  mutable std::unordered_map<std::uint64_t, SoundPath> kept_paths_;  // (source, its cell, listener cell)
  // What the listeners' cells see of the corners, for the paths not kept yet (those are exact to
  // within a cell anyway).
  static constexpr std::size_t kMemoCells = 8192;
  mutable VisibilityMemo memo_{kMemoCells};
};

// A team's acoustic model in `world` (its acoustics section, its robots' names) with `table`;
// none without a table (the threshold channel). Throws std::invalid_argument when the world has
// no acoustics section, and what AcousticModel throws.
std::unique_ptr<AcousticModel> TeamAcousticModel(const PropagationModel& propagation,
                                                 const world_sim::WorldConfig& world,
                                                 const std::shared_ptr<const DecodeTable>& table);

}  // namespace audio_propagation
