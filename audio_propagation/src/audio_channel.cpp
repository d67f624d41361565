#include "audio_propagation/audio_channel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "audio_propagation/microphone.h"
#include "grid/option_checks.h"

namespace audio_propagation {
namespace {

// Acoustic model: an arrival this far below the noise (dB) is not tracked.
constexpr double kNegligibleSnrDb = -30.0;
// Acoustic model: how often (s) the noise at each robot is worked out again.
constexpr double kNoiseUpdateSeconds = 0.05;
// Packets stamped for later that one robot may have waiting (far more than a step brings).
constexpr std::size_t kMaxPendingSends = 1000;
// Cells whose view of the corners VisibilityMemo keeps (with a path cache).
constexpr std::size_t kMemoCells = 8192;

}  // namespace

void ValidateOptions(const ChannelOptions& o) {
  grid::RequireAtLeast("audio channel capture_margin_db (dB)", o.capture_margin_db, 0.0);
  grid::RequireAtLeast("audio channel direction_noise (rad)", o.direction_noise, 0.0);
  if (!std::isfinite(o.noise_floor_db)) {
    throw std::invalid_argument("audio channel noise_floor_db must be a finite level in dB, got " +
                                std::to_string(o.noise_floor_db));
  }
  grid::RequireAbove("audio channel fate_distance (m)", o.fate_distance, 0.0);
}

AudioChannel::AudioChannel(const PropagationModel& model,
                           std::vector<world_sim::Microphone> microphones,
                           const ChannelOptions& options, const AcousticModel* acoustic)
    : model_(model),
      acoustic_(acoustic),
      microphones_(std::move(microphones)),
      options_(options),
      cache_(options.cache_size),
      // A cell's nodes are a few hundred bytes; a team's robots keep a few cells each busy.
      memo_(options.cache_size > 0 ? kMemoCells : 0),
      rng_(options.seed) {
  ValidateOptions(options_);
  nava_modem::MacOptions mac = options_.mac;
  // With the acoustic model each robot calibrates its threshold on the noise it hears at the
  // start, as a real robot does (the loudest level of its calibration time plus a margin).
  if (!mac.fixed_threshold_db && !acoustic_) mac.fixed_threshold_db = model_.options().threshold_db;
  const std::size_t n = microphones_.size();
  for (std::size_t k = 0; k < n; ++k) {
    // Robots draw their own back-offs, so adding a robot does not change the others'.
    macs_.emplace_back(mac, options_.seed * 1000003u + static_cast<std::uint32_t>(k));
  }
  tick_ = n > 0 ? macs_[0].tick_seconds() : 1.0 / (16.0 * mac.bit_rate);
  poses_.resize(n);
  levels_.assign(n, options_.noise_floor_db);
  powers_.assign(n, 0.0);
  arrivals_.resize(n);
  sending_.resize(n);
  noise_powers_.assign(n, 0.0);
  pending_per_robot_.assign(n, 0);
  level_edge_.assign(n, 0);
  finish_edge_.assign(n, 0);
  noise_ticks_ = 16 * std::max<std::int64_t>(1, std::llround(kNoiseUpdateSeconds / (16.0 * tick_)));
}

std::vector<Eigen::Vector2d> AudioChannel::Positions() const {
  std::vector<Eigen::Vector2d> at(poses_.size());
  for (std::size_t k = 0; k < poses_.size(); ++k) at[k] = poses_[k].position();
  return at;
}

void AudioChannel::UpdateNoise() {
  const std::vector<Eigen::Vector2d> at = Positions();
  acoustic_->PreparePaths(at, at);
  for (std::size_t r = 0; r < at.size(); ++r) {
    double power = 0.0;
    // What the robot's level meter reads: each noise by its share in the profile's bands.
    for (const Disturbance& d : acoustic_->NoiseAt(at[r], time(), at)) power += d.power * d.heard;
    noise_powers_[r] = power;
    level_edge_[r] = 0;  // the level is summed again at the next tick
  }
}

bool AudioChannel::Send(std::size_t robot, std::vector<std::uint8_t> data) {
  return macs_.at(robot).Enqueue(std::move(data));
}

std::int64_t AudioChannel::TickAt(double time) const {
  return std::max(ticks_, static_cast<std::int64_t>(std::ceil(time / tick_ - 1e-9)));
}

void AudioChannel::SetPoseAt(std::size_t robot, const grid::Pose2D& pose, double time) {
  if (robot >= poses_.size()) throw std::out_of_range("audio channel: no robot " + std::to_string(robot));
  PendingPose p{TickAt(time), robot, pose};
  const auto at = std::upper_bound(pending_poses_.begin(), pending_poses_.end(), p.tick,
                                   [](std::int64_t t, const PendingPose& q) { return t < q.tick; });
  pending_poses_.insert(at, std::move(p));
}

bool AudioChannel::SendAt(std::size_t robot, std::vector<std::uint8_t> data, double time) {
  if (robot >= macs_.size()) throw std::out_of_range("audio channel: no robot " + std::to_string(robot));
  // The queue's own limit is applied when the packet enters it (how full the queue is then does
  // not depend on how far the caller has advanced the channel); this one only bounds memory.
  if (pending_per_robot_[robot] >= kMaxPendingSends) {
    ++send_overflows_;
    return false;
  }
  PendingSend p{TickAt(time), robot, std::move(data)};
  const auto at = std::upper_bound(pending_sends_.begin(), pending_sends_.end(), p.tick,
                                   [](std::int64_t t, const PendingSend& q) { return t < q.tick; });
  pending_sends_.insert(at, std::move(p));
  ++pending_per_robot_[robot];
  return true;
}

void AudioChannel::ApplyPending() {
  while (!pending_poses_.empty() && pending_poses_.front().tick <= ticks_) {
    poses_[pending_poses_.front().robot] = pending_poses_.front().pose;
    pending_poses_.pop_front();
  }
  while (!pending_sends_.empty() && pending_sends_.front().tick <= ticks_) {
    PendingSend& p = pending_sends_.front();
    --pending_per_robot_[p.robot];
    if (!macs_[p.robot].Enqueue(std::move(p.data))) ++send_overflows_;
    pending_sends_.pop_front();
  }
}

double AudioChannel::LevelOf(double power) const {
  if (!(power > 0.0)) return options_.noise_floor_db;
  return acoustic_ ? 10.0 * std::log10(power) : std::max(options_.noise_floor_db, 10.0 * std::log10(power));
}

double AudioChannel::NextEventTime() const {
  if (Idle()) return std::numeric_limits<double>::infinity();
  std::int64_t next = std::numeric_limits<std::int64_t>::max();
  if (!pending_sends_.empty()) next = pending_sends_.front().tick;
  for (std::size_t r = 0; r < macs_.size(); ++r) {
    // The level changes only where an arrival starts or ends; until then it is what the next
    // tick hears.
    double power = acoustic_ ? noise_powers_[r] : 0.0;
    for (const Arrival& a : arrivals_[r]) {
      if (a.start > ticks_) next = std::min(next, a.start);
      if (!a.done) next = std::min(next, a.end);
      if (a.start <= ticks_ + 1 && ticks_ + 1 < a.end) power += a.power;
    }
    if (const std::optional<int> change = macs_[r].TicksToNextChange(LevelOf(power))) {
      next = std::min(next, ticks_ + *change);
    }
  }
  // The noise may move a carrier at its next update (and a carrier coming and going starts a
  // fresh back-off): with the air busy, every update is looked at.
  if (acoustic_) next = std::min(next, (ticks_ / noise_ticks_ + 1) * noise_ticks_);
  if (next == std::numeric_limits<std::int64_t>::max()) return std::numeric_limits<double>::infinity();
  return static_cast<double>(next) * tick_;
}

std::int64_t AudioChannel::NextWake(std::int64_t target) const {
  std::int64_t wake = target;
  if (!pending_sends_.empty()) wake = std::min(wake, pending_sends_.front().tick);
  if (acoustic_) wake = std::min(wake, (ticks_ / noise_ticks_ + 1) * noise_ticks_);
  return wake;
}

std::vector<SoundPath> AudioChannel::PathsFrom(std::size_t sender) {
  const std::size_t n = macs_.size();
  const std::vector<Eigen::Vector2d> at = Positions();
  auto compute = [&] {
    // From one source, without the n x n table Compute() would fill; no path to itself.
    std::vector<SoundPath> paths = model_.From(at[sender], at, memo_.capacity() > 0 ? &memo_ : nullptr);
    paths[sender] = SoundPath();
    return paths;
  };
  if (cache_.capacity() == 0) return compute();

  std::vector<Eigen::Vector2i> cells(n);
  for (std::size_t k = 0; k < n; ++k) cells[k] = model_.map().WorldToCell(at[k]);
  std::vector<SoundPath> paths(n);
  bool all_found = true;
  for (std::size_t r = 0; r < n && all_found; ++r) {
    if (r == sender) continue;
    std::optional<SoundPath> found = cache_.Find(cells[sender], cells[r]);
    all_found = found.has_value();
    if (found) paths[r] = std::move(*found);
  }
  if (all_found) return paths;
  paths = compute();
  for (std::size_t r = 0; r < n; ++r) {
    if (r != sender) cache_.Insert(cells[sender], cells[r], paths[r]);
  }
  return paths;
}

void AudioChannel::StartTransmission(std::size_t sender, std::vector<std::uint8_t> data, Events& events) {
  const std::size_t n = macs_.size();
  const std::int64_t duration = macs_[sender].packet_ticks();
  std::vector<SoundPath> paths = PathsFrom(sender);
  // Its past sends, but for those that can no longer overlap anything still to come.
  auto& sent = sending_[sender];
  const std::int64_t horizon = ticks_ - 4 * duration;
  sent.erase(std::remove_if(sent.begin(), sent.end(), [&](const auto& s) { return s.second < horizon; }), sent.end());
  sent.emplace_back(ticks_, ticks_ + duration);
  std::vector<double> probability;
  std::vector<Eigen::Vector2d> at;
  if (acoustic_) {
    probability.assign(n, 0.0);
    at = Positions();
  }
  for (std::size_t r = 0; r < n; ++r) {
    if (r == sender) continue;
    const std::int64_t start = ticks_ + std::llround(paths[r].travel_time / tick_);
    if (!acoustic_) {
      if (!paths[r].audible) continue;
      arrivals_[r].push_back({sender, start, start + duration, paths[r].level_db,
                              std::pow(10.0, paths[r].level_db / 10.0), data, paths[r], {}});
      NoteArrival(r, start, start + duration);
      continue;
    }
    if (!paths[r].reachable) continue;
    const LinkPrediction p = acoustic_->Predict(paths[r], at[r], acoustic_->NoiseAt(at[r], time(), at));
    probability[r] = p.probability;
    // Far below the noise an arrival changes neither the carrier nor any decision.
    if (p.snr_db < kNegligibleSnrDb) continue;
    arrivals_[r].push_back({sender, start, start + duration, p.signal.total_db,
                            std::pow(10.0, p.signal.total_db / 10.0), data, paths[r], p.signal});
    NoteArrival(r, start, start + duration);
  }
  events.started.push_back({sender, ticks_ * tick_, duration * tick_, std::move(data), std::move(paths),
                            std::move(probability)});
}

void AudioChannel::NoteArrival(std::size_t receiver, std::int64_t start, std::int64_t end) {
  level_edge_[receiver] = std::min(level_edge_[receiver], start);
  finish_edge_[receiver] = std::min(finish_edge_[receiver], end);
}

void AudioChannel::Finish(std::size_t receiver, const Arrival& a, Events& events) {
  for (const auto& [from, to] : sending_[receiver]) {
    if (from < a.end && a.start < to) {
      ++missed_while_sending_;  // half duplex: its own speaker drowns everything
      return;
    }
  }
  double loudest_other = -std::numeric_limits<double>::infinity();
  for (const Arrival& other : arrivals_[receiver]) {
    if (&other == &a || !(other.start < a.end && a.start < other.end)) continue;
    loudest_other = std::max(loudest_other, other.level_db);
  }
  Reception rx;
  rx.receiver = receiver;
  rx.sender = a.sender;
  rx.time = a.end * tick_;
  rx.level_db = a.level_db;
  rx.path_length = a.path.length;
  rx.direction = SenseDirection(microphones_[receiver], a.path.arrival_angle, poses_[receiver].yaw,
                                options_.direction_noise, rng_);
  rx.direction_confidence = std::isfinite(rx.direction) ? 1.0 : 0.0;
  if (acoustic_) {
    FinishAcoustic(receiver, a, rx);
    if (rx.kind == Reception::Kind::kNoise && rx.noise == nava_modem::RxEvent::Noise::kNone) {
      ++unheard_;  // the receiver would not have noticed it
      return;
    }
  } else if (a.level_db >= loudest_other + options_.capture_margin_db) {
    rx.kind = Reception::Kind::kPacket;
    rx.data = a.data;
  } else {
    rx.kind = Reception::Kind::kNoise;
    rx.collision = true;
  }
  events.received.push_back(std::move(rx));
}

void AudioChannel::FinishAcoustic(std::size_t receiver, const Arrival& a, Reception& rx) {
  const std::vector<Eigen::Vector2d> at = Positions();
  // The noise over the whole arrival (its mean power, as the tables define SNR), not at one moment.
  std::vector<Disturbance> disturbances = acoustic_->NoiseDuring(at[receiver], a.start * tick_, a.end * tick_, at);
  const double length = static_cast<double>(a.end - a.start);
  for (const Arrival& other : arrivals_[receiver]) {
    if (&other == &a) continue;
    const double overlap = static_cast<double>(std::min(a.end, other.end) - std::max(a.start, other.start));
    if (overlap > 0.0) disturbances.push_back({Interference::kPacket, other.power * overlap / length, 0.0});
  }
  const LinkPrediction p = acoustic_->Predict(a.path, at[receiver], disturbances);
  rx.probability = p.probability;
  rx.collision = p.kind == Interference::kPacket;
  const DecodeOutcome& o = p.outcome;
  const double u = DecisionDraw(a.sender, receiver, at);
  rx.kind = Reception::Kind::kNoise;
  using Noise = nava_modem::RxEvent::Noise;
  if (u < o.packet) {
    rx.kind = Reception::Kind::kPacket;
    rx.data = a.data;
  } else if (u < o.packet + o.zero_byte) {
    rx.noise = Noise::kZeroByte;
  } else if (u < o.packet + o.zero_byte + o.one_byte) {
    rx.noise = Noise::kOneByte;
  } else if (u < o.packet + o.zero_byte + o.one_byte + o.bad_crc) {
    rx.noise = Noise::kBadCrc;
  }
}

double AudioChannel::DecisionDraw(std::size_t sender, std::size_t listener, const std::vector<Eigen::Vector2d>& at) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  if (!options_.link_fate) return uniform(rng_);
  const std::size_t n = macs_.size();
  if (fates_.empty()) fates_.resize(n * n);
  Fate& f = fates_[sender * n + listener];
  if (!f.drawn || (at[sender] - f.sender).norm() > options_.fate_distance ||
      (at[listener] - f.listener).norm() > options_.fate_distance) {
    f = Fate{true, at[sender], at[listener], uniform(rng_)};
  }
  return f.draw;
}

bool AudioChannel::Quiet() const {
  for (std::size_t r = 0; r < macs_.size(); ++r) {
    if (!macs_[r].Idle()) return false;
    // With an acoustic model the noise is always there: quiet while it stays below the carrier
    // threshold (it is checked again every bit once the medium is busy).
    const bool silent = acoustic_ ? powers_[r] == noise_powers_[r] && !macs_[r].carrier() &&
                                        levels_[r] < macs_[r].threshold_db()
                                  : levels_[r] == options_.noise_floor_db;
    if (!silent) return false;
    for (const Arrival& a : arrivals_[r]) {
      if (!a.done) return false;
    }
  }
  return true;
}

AudioChannel::Events AudioChannel::AdvanceTo(double time) {
  Events events;
  const std::int64_t target = static_cast<std::int64_t>(std::floor(time / tick_ + 1e-9));
  const std::size_t n = macs_.size();
  while (ticks_ < target) {
    ApplyPending();
    // The noise changes as robots move a cell or a source turns on or off: every 50 ms is often
    // enough, and the check for quiet below runs on the same bit boundaries.
    if (acoustic_ && ticks_ % noise_ticks_ == 0) UpdateNoise();
    // Long silences (robots that say something every few seconds) are skipped in one go, up to
    // the next moment something is due (a stamped send, the noise's update); the check runs
    // once a bit, so at most a bit of silence is ticked through. A silent tick of an idle MAC
    // changes nothing but its count, so how the silence is cut up does not change the run.
    if (ticks_ % 16 == 0 && Quiet()) {
      const std::int64_t wake = NextWake(target);
      for (nava_modem::CsmaMac& mac : macs_) mac.SkipIdle(static_cast<std::uint64_t>(wake - ticks_));
      ticks_ = wake;
      continue;
    }
    ++ticks_;
    for (std::size_t r = 0; r < n; ++r) {
      // The level only changes where an arrival starts or ends (or the noise is updated): the
      // sum is taken again there, and only there (a big team hears dozens of arrivals).
      if (ticks_ >= level_edge_[r]) {
        double power = acoustic_ ? noise_powers_[r] : 0.0;  // linear sum of what is arriving now
        std::int64_t edge = std::numeric_limits<std::int64_t>::max();
        for (const Arrival& a : arrivals_[r]) {
          if (a.start <= ticks_ && ticks_ < a.end) power += a.power;
          if (a.start > ticks_) edge = std::min(edge, a.start);
          else if (a.end > ticks_) edge = std::min(edge, a.end);
        }
        level_edge_[r] = edge;
        if (power != powers_[r]) {
          powers_[r] = power;
          levels_[r] = LevelOf(power);
        }
      }
      if (auto packet = macs_[r].Tick(levels_[r])) StartTransmission(r, std::move(*packet), events);
    }
    for (std::size_t r = 0; r < n; ++r) {
      if (ticks_ < finish_edge_[r]) continue;
      std::int64_t edge = std::numeric_limits<std::int64_t>::max();
      for (Arrival& a : arrivals_[r]) {
        if (!a.done && a.end <= ticks_) {
          Finish(r, a, events);
          a.done = true;
        }
        if (!a.done) edge = std::min(edge, a.end);
      }
      finish_edge_[r] = edge;
      // Forget what can no longer overlap anything still to come.
      const std::int64_t horizon = ticks_ - 4 * macs_[r].packet_ticks();
      while (!arrivals_[r].empty() && arrivals_[r].front().done && arrivals_[r].front().end < horizon) {
        arrivals_[r].pop_front();
      }
    }
  }
  return events;
}

}  // namespace audio_propagation
