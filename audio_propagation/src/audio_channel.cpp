#include "audio_propagation/audio_channel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "audio_propagation/acoustic_reception.h"
#include "audio_propagation/microphone.h"
#include "audio_propagation/threshold_reception.h"
#include "grid/option_checks.h"

namespace audio_propagation {
namespace {

// Packets stamped for later that one robot may have waiting (far more than a step brings).
constexpr std::size_t kMaxPendingSends = 1000;
// Cells whose view of the corners VisibilityMemo keeps (with a path cache).
constexpr std::size_t kMemoCells = 8192;

// The reception model the channel's options and an acoustic model (or none) ask for.
std::unique_ptr<ReceptionModel> MakeReception(const PropagationModel& model, const ChannelOptions& options,
                                              const AcousticModel* acoustic) {
  ValidateOptions(options);
  if (acoustic) return std::make_unique<AcousticReception>(*acoustic, options.noise_floor_db);
  return std::make_unique<ThresholdReception>(model.options().threshold_db, options.capture_margin_db,
                                              options.noise_floor_db);
}

}  // namespace

void ValidateOptions(const ChannelOptions& o) {
  grid::RequireAtLeast("audio channel capture_margin_db (dB)", o.capture_margin_db, 0.0);
  grid::RequireAtLeast("audio channel direction_noise (rad)", o.direction_noise, 0.0);
  if (!std::isfinite(o.noise_floor_db)) {
    throw std::invalid_argument("audio channel noise_floor_db must be a finite level in dB, got " +
                                std::to_string(o.noise_floor_db));
  }
  grid::RequireAbove("audio channel fate_distance (m)", o.fate_distance, 0.0);
  if (o.direction_errors && o.direction_noise > 0.0) {
    throw std::invalid_argument("audio channel direction_noise is unused with a direction table (it gives each report's error)");
  }
}

AudioChannel::AudioChannel(const PropagationModel& model, std::vector<world_sim::Microphone> microphones,
                           const ChannelOptions& options, const AcousticModel* acoustic)
    : AudioChannel(model, std::move(microphones), options, MakeReception(model, options, acoustic)) {}

AudioChannel::AudioChannel(const PropagationModel& model, std::vector<world_sim::Microphone> microphones,
                           const ChannelOptions& options, std::unique_ptr<ReceptionModel> reception)
    : model_(model),
      reception_(std::move(reception)),
      microphones_(std::move(microphones)),
      options_(options),
      cache_(options.cache_size),
      // A cell's nodes are a few hundred bytes; a team's robots keep a few cells each busy.
      memo_(options.cache_size > 0 ? kMemoCells : 0),
      rng_(options.seed) {
  ValidateOptions(options_);
  if (!reception_) throw std::invalid_argument("audio channel: expected a reception model, got none");
  if (options_.direction_errors && !reception_->acoustic()) {
    throw std::invalid_argument("audio channel: measured direction errors need the acoustic channel model (each link's "
                                "DRR and RT60 pick the table's cell); the threshold model has neither");
  }
  nava_modem::MacOptions mac = options_.mac;
  // Unless the model fixes one, each robot calibrates its threshold on the noise it hears at the
  // start, as a real robot does (the loudest level of its calibration time plus a margin).
  if (!mac.fixed_threshold_db) mac.fixed_threshold_db = reception_->CarrierThresholdDb();
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
  background_.power.assign(n, 0.0);
  pending_.per_robot.assign(n, 0);
  level_edge_.assign(n, 0);
  finish_edge_.assign(n, 0);
  const double every = reception_->BackgroundSeconds();
  if (every > 0.0) background_.ticks = 16 * std::max<std::int64_t>(1, std::llround(every / (16.0 * tick_)));
}

const std::vector<Eigen::Vector2d>& AudioChannel::Positions() {
  if (positions_stale_) {
    positions_.resize(poses_.size());
    for (std::size_t k = 0; k < poses_.size(); ++k) positions_[k] = poses_[k].position();
    positions_stale_ = false;
  }
  return positions_;
}

void AudioChannel::UpdateBackground() {
  reception_->Background(time(), Positions(), background_.power);
  std::fill(level_edge_.begin(), level_edge_.end(), 0);  // each level is summed again at the next tick
}

std::int64_t AudioChannel::NextBackgroundTick() const {
  return background_.ticks > 0 ? (ticks_ / background_.ticks + 1) * background_.ticks : std::numeric_limits<std::int64_t>::max();
}

bool AudioChannel::Send(std::size_t robot, nava_modem::MacFrame frame) {
  return macs_.at(robot).Enqueue(std::move(frame));
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
  const auto at = std::upper_bound(pending_.poses.begin(), pending_.poses.end(), p.tick,
                                   [](std::int64_t t, const PendingPose& q) { return t < q.tick; });
  pending_.poses.insert(at, std::move(p));
}

bool AudioChannel::SendAt(std::size_t robot, std::vector<std::uint8_t> data, double time) {
  return SendAt(robot, macs_.at(robot).Packet(std::move(data)), time);
}

bool AudioChannel::SendAt(std::size_t robot, nava_modem::MacFrame frame, double time) {
  if (robot >= macs_.size()) throw std::out_of_range("audio channel: no robot " + std::to_string(robot));
  // Refused now, not when it enters the queue in the middle of a later AdvanceTo().
  nava_modem::ValidateMacFrame(frame);
  // The queue's own limit is applied when the packet enters it (how full the queue is then does
  // not depend on how far the caller has advanced the channel); this one only bounds memory.
  if (pending_.per_robot[robot] >= kMaxPendingSends) {
    ++counts_.send_overflows;
    return false;
  }
  PendingSend p{TickAt(time), robot, std::move(frame)};
  const auto at = std::upper_bound(pending_.sends.begin(), pending_.sends.end(), p.tick,
                                   [](std::int64_t t, const PendingSend& q) { return t < q.tick; });
  pending_.sends.insert(at, std::move(p));
  ++pending_.per_robot[robot];
  return true;
}

void AudioChannel::ApplyPending() {
  while (!pending_.poses.empty() && pending_.poses.front().tick <= ticks_) {
    poses_[pending_.poses.front().robot] = pending_.poses.front().pose;
    positions_stale_ = true;
    pending_.poses.pop_front();
  }
  while (!pending_.sends.empty() && pending_.sends.front().tick <= ticks_) {
    PendingSend& p = pending_.sends.front();
    --pending_.per_robot[p.robot];
    if (!macs_[p.robot].Enqueue(std::move(p.frame))) ++counts_.send_overflows;
    pending_.sends.pop_front();
  }
}

double AudioChannel::NextEventTime() const {
  if (Idle()) return std::numeric_limits<double>::infinity();
  std::int64_t next = std::numeric_limits<std::int64_t>::max();
  if (!pending_.sends.empty()) next = pending_.sends.front().tick;
  for (std::size_t r = 0; r < macs_.size(); ++r) {
    // The level changes only where an arrival starts or ends; until then it is what the next
    // tick hears.
    double power = background_.power[r];
    for (const Arrival& a : arrivals_[r]) {
      if (a.start > ticks_) next = std::min(next, a.start);
      if (!a.done) next = std::min(next, a.end);
      if (a.start <= ticks_ + 1 && ticks_ + 1 < a.end) power += a.power;
    }
    if (const std::optional<int> change = macs_[r].TicksToNextChange(reception_->LevelDb(power))) {
      next = std::min(next, ticks_ + *change);
    }
  }
  // The background may move a carrier at its next update (and a carrier coming and going starts
  // a fresh back-off): with the air busy, every update is looked at.
  next = std::min(next, NextBackgroundTick());
  if (next == std::numeric_limits<std::int64_t>::max()) return std::numeric_limits<double>::infinity();
  return static_cast<double>(next) * tick_;
}

std::int64_t AudioChannel::NextWake(std::int64_t target) const {
  std::int64_t wake = target;
  if (!pending_.sends.empty()) wake = std::min(wake, pending_.sends.front().tick);
  return std::min(wake, NextBackgroundTick());
}

std::vector<SoundPath> AudioChannel::PathsFrom(std::size_t sender) {
  const std::size_t n = macs_.size();
  const std::vector<Eigen::Vector2d>& at = Positions();
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

void AudioChannel::StartTransmission(std::size_t sender, nava_modem::MacFrame frame, Events& events) {
  const std::size_t n = macs_.size();
  const std::int64_t duration = std::max(1, macs_[sender].Ticks(frame.airtime));
  longest_ticks_ = std::max(longest_ticks_, duration);
  std::vector<SoundPath> paths = PathsFrom(sender);
  std::vector<std::uint8_t>& data = frame.data;
  // Its past sends, but for those that can no longer overlap anything still to come.
  auto& sent = sending_[sender];
  const std::int64_t horizon = ticks_ - 4 * longest_ticks_;
  sent.erase(std::remove_if(sent.begin(), sent.end(), [&](const auto& s) { return s.second < horizon; }), sent.end());
  sent.emplace_back(ticks_, ticks_ + duration);
  std::vector<double> probability;
  if (reception_->Predicts()) probability.assign(n, 0.0);
  const std::vector<Eigen::Vector2d>& at = Positions();
  for (std::size_t r = 0; r < n; ++r) {
    if (r == sender) continue;
    const ArrivalSound sound = reception_->Arrive(paths[r], r, at, time());
    if (sound.probability && !probability.empty()) probability[r] = *sound.probability;
    if (!sound.level_db) continue;  // nothing this robot would notice
    const std::int64_t start = ticks_ + std::llround(paths[r].travel_time / tick_);
    arrivals_[r].push_back({sender, start, start + duration, *sound.level_db, std::pow(10.0, *sound.level_db / 10.0), data,
                            frame.rate, paths[r]});
    NoteArrival(r, start, start + duration);
  }
  events.started.push_back({sender, ticks_ * tick_, duration * tick_, std::move(data), frame.rate, std::move(paths),
                            std::move(probability)});
}

void AudioChannel::NoteArrival(std::size_t receiver, std::int64_t start, std::int64_t end) {
  level_edge_[receiver] = std::min(level_edge_[receiver], start);
  finish_edge_[receiver] = std::min(finish_edge_[receiver], end);
}

void AudioChannel::Finish(std::size_t receiver, const Arrival& a, Events& events) {
  for (const auto& [from, to] : sending_[receiver]) {
    if (from < a.end && a.start < to) {
      ++counts_.missed_while_sending;  // half duplex: its own speaker drowns everything
      return;
    }
  }
  // What overlapped it there, in the order it arrived.
  std::vector<Overlap> overlaps;
  const double length = static_cast<double>(a.end - a.start);
  for (const Arrival& other : arrivals_[receiver]) {
    if (&other == &a || !(other.start < a.end && a.start < other.end)) continue;
    const double overlap = static_cast<double>(std::min(a.end, other.end) - std::max(a.start, other.start));
    overlaps.push_back({other.level_db, other.power * overlap / length});
  }
  Reception rx;
  rx.receiver = receiver;
  rx.sender = a.sender;
  rx.time = a.end * tick_;
  rx.level_db = a.level_db;
  rx.path_length = a.path.length;
  const std::vector<Eigen::Vector2d>& at = Positions();
  if (options_.direction_errors) {
    const LinkLevels levels = reception_->acoustic()->Levels(a.path, at[receiver]);
    const SensedDirection sensed = SenseDirection(microphones_[receiver], a.path.arrival_angle, poses_[receiver].yaw,
                                                  *options_.direction_errors, levels.drr_db, levels.rt60, rng_);
    rx.direction = sensed.direction;
    rx.direction_confidence = sensed.confidence;
  } else {
    rx.direction = SenseDirection(microphones_[receiver], a.path.arrival_angle, poses_[receiver].yaw,
                                  options_.direction_noise, rng_);
    rx.direction_confidence = std::isfinite(rx.direction) ? 1.0 : 0.0;
  }
  const Decision d = reception_->Decide(a.path, receiver, a.level_db, a.start * tick_, a.end * tick_, overlaps, at,
                                        [&] { return DecisionDraw(a.sender, receiver, at); });
  if (!d.heard) {
    ++counts_.unheard;  // the receiver would not have noticed it
    return;
  }
  rx.kind = d.packet ? Reception::Kind::kPacket : Reception::Kind::kNoise;
  if (d.packet) {
    rx.data = a.data;
    rx.rate = a.rate;
  }
  rx.collision = d.collision;
  rx.noise = d.noise;
  rx.probability = d.probability;
  events.received.push_back(std::move(rx));
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
    // (Checked again every bit once the medium is busy.)
    if (!reception_->Quiet(powers_[r], background_.power[r], levels_[r], macs_[r])) return false;
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
    // The background changes as robots move a cell or a source turns on or off: every so often
    // is enough, and the check for quiet below runs on the same bit boundaries.
    if (background_.ticks > 0 && ticks_ % background_.ticks == 0) UpdateBackground();
    // Long silences (robots that say something every few seconds) are skipped in one go, up to
    // the next moment something is due (a stamped send, the noise's update); the check runs
    // once a bit, so at most a bit of silence is ticked through. A silent tick of an idle MAC
    // changes nothing but its count and its floor, which hears the same steady level in one go,
    // so how the silence is cut up does not change the run.
    if (ticks_ % 16 == 0 && Quiet()) {
      const std::int64_t wake = NextWake(target);
      for (std::size_t r = 0; r < n; ++r) macs_[r].SkipIdle(static_cast<std::uint64_t>(wake - ticks_), levels_[r]);
      ticks_ = wake;
      continue;
    }
    ++ticks_;
    for (std::size_t r = 0; r < n; ++r) {
      // The level only changes where an arrival starts or ends (or the noise is updated): the
      // sum is taken again there, and only there (a big team hears dozens of arrivals).
      if (ticks_ >= level_edge_[r]) {
        double power = background_.power[r];  // linear sum of what is arriving now
        std::int64_t edge = std::numeric_limits<std::int64_t>::max();
        for (const Arrival& a : arrivals_[r]) {
          if (a.start <= ticks_ && ticks_ < a.end) power += a.power;
          if (a.start > ticks_) edge = std::min(edge, a.start);
          else if (a.end > ticks_) edge = std::min(edge, a.end);
        }
        level_edge_[r] = edge;
        if (power != powers_[r]) {
          powers_[r] = power;
          levels_[r] = reception_->LevelDb(power);
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
      const std::int64_t horizon = ticks_ - 4 * longest_ticks_;
      while (!arrivals_[r].empty() && arrivals_[r].front().done && arrivals_[r].front().end < horizon) {
        arrivals_[r].pop_front();
      }
    }
  }
  return events;
}

}  // namespace audio_propagation
