#include "audio_propagation/acoustic_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "audio_propagation/carrier_share.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/recorded_noise.h"
#include "nava_modem/wav_file.h"

namespace audio_propagation {
namespace {

double Power(double db) { return std::pow(10.0, db / 10.0); }
double Db(double power) { return 10.0 * std::log10(power); }

// Barron's revised theory: the reflected energy falls as exp(-0.04 r / T) with the distance r
// the sound has come, i.e. 10 log10(e) * 0.04 = 0.174 dB per metre per second of RT60.
constexpr double kReverberantDecay = 0.174;

// How much of a whine a receiver minds, as a fraction of its power, for a table without a
// measured whine harm curve (room's: its tones fill its band): each harmonic (1x, 2x and
// 3x, at 0, -6 and -12 dB in amplitude) that falls within the band widened by 10 % each side
// counts by its share of the power, and, for a profile with a few tones (`tones`, empty for one
// whose tones fill its band), by how close it comes to a tone: fully within half a bit-rate
// of one, falling as the square of the distance beyond, to a floor of -10 dB (nava_decode copes
// with a whine between its tones some 10 dB louder than one on a tone).
double WhineHarm(double hz, double low, double high, const std::vector<double>& tones) {
  const double weights[3] = {1.0, 0.25, 0.0625};
  constexpr double kNear = 150.0;  // Hz: half of nava's 300 bit/s
  double harm = 0.0, all = 0.0;
  for (int h = 0; h < 3; ++h) {
    const double f = hz * (h + 1);
    all += weights[h];
    if (f < 0.9 * low || f > 1.1 * high) continue;
    double closeness = 1.0;
    if (!tones.empty()) {
      double gap = 1e300;
      for (double t : tones) gap = std::min(gap, std::abs(f - t));
      closeness = std::clamp((kNear / std::max(gap, 1.0)) * (kNear / std::max(gap, 1.0)), 0.1, 1.0);
    }
    harm += weights[h] * closeness;
  }
  return harm / all;
}

// A noise source's Disturbance::listened, Disturbance::heard and Disturbance::recording for
// `profile`, at the rate the tables are rendered at; a recording's are read from its file.
struct SourceWeights {
  double listened = 1.0;
  double heard = 1.0;
  std::shared_ptr<const nava_modem::RecordingWeight> recording;
};

SourceWeights WeightsOf(const world_sim::NoiseSourceSpec& source, nava_modem::Profile profile) {
  if (source.kind != world_sim::NoiseKind::kRecording) {
    return {1.0, CarrierShare(source.kind, source.frequency, profile, kTableSampleRate), nullptr};
  }
  try {
    const nava_modem::Audio audio = nava_modem::ReadAudioFile(source.file);
    auto weight =
        std::make_shared<const nava_modem::RecordingWeight>(audio.samples, audio.sample_rate, profile, kTableSampleRate);
    return {std::pow(10.0, -weight->in_band_offset_db() / 10.0), weight->in_band_fraction(), weight};
  } catch (const std::exception& e) {
    throw std::invalid_argument("acoustic model: noise source '" + source.name + "' (" + source.file + "): " + e.what());
  }
}

void RequireRoom(const world_sim::RoomAcoustics& room, const std::string& where) {
  if (!(room.rt60 > 0.0 && room.rt60 <= 10.0)) {
    throw std::invalid_argument("acoustic model: " + where + ".rt60 must be in (0, 10] s, got " +
                                std::to_string(room.rt60));
  }
  if (!(world_sim::CriticalDistance(room) > 0.0)) {
    throw std::invalid_argument("acoustic model: " + where + " needs a volume or a critical_distance above 0");
  }
}

}  // namespace

DecodeOutcome PredictOutcome(const DecodeTable& table, Interference kind, double snr_db, double drr_db, double rt60) {
  DecodeOutcome o = table.Lookup(kind, snr_db, drr_db, rt60);
  // Below the quietest SNR measured the table holds its last figures; the receiver does not:
  // whatever it still made of a packet fades out over kFadeBelowTableDb.
  const double below = table.snr_db.front() - snr_db;
  if (below > 0.0) {
    const double keep = std::max(0.0, 1.0 - below / kFadeBelowTableDb);
    o.packet *= keep;
    o.zero_byte *= keep;
    o.one_byte *= keep;
    o.bad_crc *= keep;
  }
  return o;
}

DecodeOutcome PredictOutcome(const DecodeTable& table, Interference kind, const std::vector<double>& snrs_db,
                             double drr_db, double rt60) {
  if (snrs_db.empty()) throw std::invalid_argument("PredictOutcome: no SNR to predict at");
  DecodeOutcome mean;
  for (double snr : snrs_db) {
    const DecodeOutcome o = PredictOutcome(table, kind, snr, drr_db, rt60);
    mean.packet += o.packet;
    mean.zero_byte += o.zero_byte;
    mean.one_byte += o.one_byte;
    mean.bad_crc += o.bad_crc;
  }
  const auto n = static_cast<double>(snrs_db.size());
  return {mean.packet / n, mean.zero_byte / n, mean.one_byte / n, mean.bad_crc / n};
}

double AcousticThresholdDb(const world_sim::Acoustics& acoustics) { return acoustics.ambient_db - 30.0; }

void UseAcousticPropagation(PropagationOptions& options, const world_sim::Acoustics& acoustics, bool keep_range) {
  if (!keep_range) options.max_range = 0.0;
  options.threshold_db = std::min(options.threshold_db, AcousticThresholdDb(acoustics));
}

LinkLevels LinkBudget(double source_db, double d0, double length, int corners, double corner_loss_db,
                      const world_sim::RoomAcoustics& room, double coupling_db, bool barron) {
  LinkLevels l;
  const double d = std::max(length, d0);
  l.rt60 = room.rt60;
  l.direct_db = source_db - 20.0 * std::log10(d / d0) - corner_loss_db * std::max(corners, 0);
  l.reverberant_db = source_db - 20.0 * std::log10(world_sim::CriticalDistance(room) / d0) -
                     (barron ? kReverberantDecay * length / room.rt60 : 0.0) + coupling_db;
  l.total_db = Db(Power(l.direct_db) + Power(l.reverberant_db));
  l.drr_db = l.direct_db - l.reverberant_db;
  return l;
}

double CriticalDistanceFromDrr(double drr_db, double distance, double rt60) {
  // drr = 20 log10(rc / d) + kReverberantDecay d / rt60 (LinkBudget with d0 = 1 m, no corners).
  return distance * std::pow(10.0, (drr_db - kReverberantDecay * distance / rt60) / 20.0);
}

AcousticModel::AcousticModel(const PropagationModel& propagation, world_sim::Acoustics acoustics,
                             DecodeTable table, std::vector<std::string> robot_names)
    : propagation_(propagation),
      acoustics_(std::move(acoustics)),
      table_(std::move(table)),
      robot_names_(std::move(robot_names)) {
  RequireRoom(acoustics_.room, "acoustics");
  for (const world_sim::AcousticRegion& r : acoustics_.regions) RequireRoom(r.room, "region '" + r.name + "'");
  if (!(acoustics_.corner_loss_db >= 0.0)) {
    throw std::invalid_argument("acoustic model: corner_loss_db must be >= 0 dB");
  }
  if (table_.cells.empty()) throw std::invalid_argument("acoustic model: the decode table is empty");
  if (table_.profile == "nava") {
    const nava_modem::ModemOptions modem;  // the thesis's tones, which the table was measured with
    tones_ = {modem.mark_hz, modem.space_hz};
  }
  const auto profile = nava_modem::ParseProfile(table_.profile);
  if (!profile) throw std::invalid_argument("acoustic model: the table's profile '" + table_.profile + "' is unknown");
  ambient_heard_ = CarrierShare(acoustics_.ambient_kind, 0.0, *profile, kTableSampleRate);
  whine_settle_s_ = nava_modem::WhineSettleSeconds(*profile);
  for (const world_sim::NoiseSourceSpec& s : acoustics_.noise_sources) {
    const SourceWeights w = WeightsOf(s, *profile);
    source_listened_.push_back(w.listened);
    source_heard_.push_back(w.heard);
    source_recording_.push_back(w.recording);
    if (s.robot.empty()) {
      if (!propagation_.map().IsFreeAt({s.x, s.y})) {
        throw std::invalid_argument("acoustic model: noise source '" + s.name + "' at (" + std::to_string(s.x) +
                                    ", " + std::to_string(s.y) + ") is not in the map's free space");
      }
      source_robot_.push_back(-1);
      continue;
    }
    const auto it = std::find(robot_names_.begin(), robot_names_.end(), s.robot);
    if (it == robot_names_.end()) {
      throw std::invalid_argument("acoustic model: noise source '" + s.name + "' rides on robot '" + s.robot +
                                  "', which is not in the team");
    }
    source_robot_.push_back(static_cast<int>(it - robot_names_.begin()));
  }
  if (acoustics_.rooms) {
    try {
      rooms_ = std::make_unique<const RoomCoupling>(propagation_.map(), acoustics_);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("acoustic model: acoustics.rooms: ") + e.what());
    }
  }
}

AcousticModel::Field AcousticModel::FieldBetween(const Eigen::Vector2d& from, const Eigen::Vector2d& at) const {
  if (rooms_) {
    const int source = rooms_->ZoneAt(from), listener = rooms_->ZoneAt(at);
    if (source >= 0 && listener >= 0) {
      // The source's zone sets how loud its field is (the critical distance), the listener's how
      // it falls and how it decays at the receiver.
      world_sim::RoomAcoustics room;
      room.rt60 = rooms_->ZoneAcoustics(static_cast<std::size_t>(listener)).rt60;
      room.critical_distance = world_sim::CriticalDistance(rooms_->ZoneAcoustics(static_cast<std::size_t>(source)));
      // Barron's fall is the time the direct sound takes to cross the source's own field; a
      // field further on is reached later still, through the openings, and the coupling is its
      // whole fall.
      return {room,
              rooms_->field().RelativeLevelDb(static_cast<std::size_t>(source), static_cast<std::size_t>(listener)),
              source == listener};
    }
  }
  return {acoustics_.RoomAt(at.x(), at.y()), 0.0};
}

LinkLevels AcousticModel::Levels(const SoundPath& path, const Eigen::Vector2d& listener) const {
  const PropagationOptions& o = propagation_.options();
  const Field field = FieldBetween(path.polyline.empty() ? listener : path.polyline.front(), listener);
  return LinkBudget(o.source_level_db, o.reference_distance, path.length, path.bends, acoustics_.corner_loss_db,
                    field.room, field.coupling_db, field.barron);
}

std::vector<Disturbance> AcousticModel::NoiseAt(const Eigen::Vector2d& at, double t,
                                                const std::vector<Eigen::Vector2d>& robots) const {
  return NoiseDuring(at, t, t, robots);
}

std::vector<Disturbance> AcousticModel::NoiseDuring(const Eigen::Vector2d& at, double t0, double t1,
                                                    const std::vector<Eigen::Vector2d>& robots) const {
  std::vector<Disturbance> out;
  out.push_back({FromNoiseKind(acoustics_.ambient_kind), Power(acoustics_.ambient_db), 0.0, 1.0, ambient_heard_});
  for (std::size_t k = 0; k < acoustics_.noise_sources.size(); ++k) {
    const world_sim::NoiseSourceSpec& s = acoustics_.noise_sources[k];
    const double sounding = world_sim::SoundingFraction(s, t0, t1);
    if (sounding <= 0.0) continue;
    const std::optional<double> level = SourceLevelDb(k, at, robots);
    if (!level) continue;
    // A whine that started less than the receiver's whitening memory ago is still a plain tone to
    // it, not yet notched; the table's whine cells are the steady state, a tone already whitened
    // away. It is judged on the white cells at the power of its harmonics in the receiver's band.
    // Measured in the hospital's validation (pump 900 Hz, every harmonic in band, on 4 s of every
    // 8): so judged, the model agrees within 7 points; as white noise with that much power in the
    // band alone (6.6 dB more), as the chirp detector's matched filter would spread it, it was 25
    // points under the rendered delivery: the hopping data tones meet it one tone at a time.
    if (s.kind == world_sim::NoiseKind::kWhine && world_sim::SoundingFor(s, t0) < whine_settle_s_) {
      out.push_back({Interference::kWhite, sounding * Power(*level), 0.0, source_heard_[k], source_heard_[k], nullptr});
      continue;
    }
    out.push_back({FromNoiseKind(s.kind), sounding * Power(*level), s.frequency, source_listened_[k],
                   source_heard_[k], source_recording_[k].get()});
  }
  return out;
}

std::optional<Eigen::Vector2d> AcousticModel::SourcePosition(std::size_t k,
                                                            const std::vector<Eigen::Vector2d>& robots) const {
  const world_sim::NoiseSourceSpec& s = acoustics_.noise_sources.at(k);
  if (source_robot_[k] < 0) return Eigen::Vector2d(s.x, s.y);
  if (static_cast<std::size_t>(source_robot_[k]) >= robots.size()) return std::nullopt;
  return robots[static_cast<std::size_t>(source_robot_[k])];
}

std::optional<double> AcousticModel::SourceLevelDb(std::size_t k, const Eigen::Vector2d& at,
                                                   const std::vector<Eigen::Vector2d>& robots) const {
  const world_sim::NoiseSourceSpec& s = acoustics_.noise_sources.at(k);
  const std::optional<Eigen::Vector2d> from = SourcePosition(k, robots);
  if (!from) return std::nullopt;
  // A robot's own motors are right by its microphone: heard at their 1 m level, direct.
  if ((*from - at).norm() < 1e-9) return s.level_db;
  const SoundPath p = PathBetween(k, *from, at);
  if (!p.reachable) return std::nullopt;
  const PropagationOptions& o = propagation_.options();
  const Field field = FieldBetween(*from, at);
  return LinkBudget(s.level_db, o.reference_distance, p.length, p.bends, acoustics_.corner_loss_db, field.room,
                    field.coupling_db, field.barron)
      .total_db;
}

std::uint64_t AcousticModel::PathKey(std::size_t source, const Eigen::Vector2d& from, const Eigen::Vector2d& to) const {
  const grid::OccupancyMap& map = propagation_.map();
  const Eigen::Vector2i a = map.WorldToCell(from), b = map.WorldToCell(to);
  auto bits = [](int v) { return static_cast<std::uint64_t>(v) & 0x3fffu; };  // 14 bits a coordinate
  return (static_cast<std::uint64_t>(source & 0xffu) << 56) | (bits(a.x()) << 42) | (bits(a.y()) << 28) |
         (bits(b.x()) << 14) | bits(b.y());
}

void AcousticModel::Keep(std::uint64_t key, SoundPath path) const {
  if (kept_paths_.size() > kMaxKeptPaths) kept_paths_.clear();
  path.polyline.clear();  // only the length and corners are needed
  kept_paths_.emplace(key, std::move(path));
}

SoundPath AcousticModel::PathBetween(std::size_t source, const Eigen::Vector2d& from,
                                     const Eigen::Vector2d& to) const {
  // Paths are kept by (source, its cell, the listener's cell): a listener standing still, or a
  // robot carrying its motors past the same cells again, costs a lookup.
  const std::uint64_t key = PathKey(source, from, to);
  const auto it = kept_paths_.find(key);
  if (it != kept_paths_.end()) return it->second;
  Keep(key, std::move(propagation_.From(from, {to}, &memo_).front()));
  return kept_paths_.at(key);
}

void AcousticModel::PreparePaths(const std::vector<Eigen::Vector2d>& listeners,
                                 const std::vector<Eigen::Vector2d>& robots) const {
  for (std::size_t k = 0; k < acoustics_.noise_sources.size(); ++k) {
    const std::optional<Eigen::Vector2d> from = SourcePosition(k, robots);
    if (!from) continue;
    std::vector<Eigen::Vector2d> missing;
    std::vector<std::uint64_t> keys;
    for (const Eigen::Vector2d& at : listeners) {
      const std::uint64_t key = PathKey(k, *from, at);
      if ((*from - at).norm() < 1e-9 || kept_paths_.count(key) ||
          std::find(keys.begin(), keys.end(), key) != keys.end()) {
        continue;
      }
      missing.push_back(at);
      keys.push_back(key);
    }
    if (missing.empty()) continue;
    // One search from the source serves every listener (it sees its corners once).
    std::vector<SoundPath> paths = propagation_.From(*from, missing, &memo_);
    for (std::size_t m = 0; m < missing.size(); ++m) Keep(keys[m], std::move(paths[m]));
  }
}

double AcousticModel::EffectivePower(const Disturbance& d) const {
  if (d.kind != Interference::kWhine) return d.power * d.listened;
  // Measured: how much more this whine harms the receiver than the table's own (whine_harm.h).
  if (!table_.whine_harm_hz.empty()) return d.power * std::pow(10.0, table_.WhineHarmDb(d.frequency) / 10.0);
  const double reference = WhineHarm(table_.whine_hz, table_.band_low_hz, table_.band_high_hz, tones_);
  const double here = WhineHarm(d.frequency, table_.band_low_hz, table_.band_high_hz, tones_);
  // Out of band a whine still leaks a little through the receiver's filters (-20 dB).
  return d.power * std::max(here, 0.01) / std::max(reference, 0.01);
}

LinkPrediction AcousticModel::Predict(const SoundPath& path, const Eigen::Vector2d& listener,
                                      const std::vector<Disturbance>& disturbances) const {
  LinkPrediction p;
  p.path_length = path.length;
  p.corners = path.bends;
  p.signal = Levels(path, listener);
  double noise = 0.0, loudest = -1.0, loudest_recording = 0.0;
  const nava_modem::RecordingWeight* recording = nullptr;
  for (const Disturbance& d : disturbances) {
    const double power = EffectivePower(d);
    noise += power;
    if (power > loudest) {
      loudest = power;
      p.kind = d.kind;
    }
    if (d.recording && power > loudest_recording) {
      loudest_recording = power;
      recording = d.recording;
    }
  }
  noise = std::max(noise, 1e-30);
  p.noise_db = Db(noise);
  p.snr_db = p.signal.total_db - p.noise_db;
  // The loudest recording is weighed over the receiver's cells, the rest of the noise as steady.
  p.outcome = recording ? PredictOutcome(table_, p.kind, recording->TableSnrsDb(p.snr_db, loudest_recording / noise),
                                         p.signal.drr_db, p.signal.rt60)
                        : PredictOutcome(table_, p.kind, p.snr_db, p.signal.drr_db, p.signal.rt60);
  p.probability = p.outcome.packet;
  return p;
}

std::unique_ptr<AcousticModel> TeamAcousticModel(const PropagationModel& propagation,
                                                 const world_sim::WorldConfig& world,
                                                 const std::shared_ptr<const DecodeTable>& table) {
  if (!table) return nullptr;
  if (!world.acoustics) throw std::invalid_argument("the acoustic channel model needs a world with an acoustics section");
  std::vector<std::string> names;
  for (const world_sim::RobotSpec& r : world.robots) names.push_back(r.name);
  return std::make_unique<AcousticModel>(propagation, *world.acoustics, *table, names);
}

}  // namespace audio_propagation
