#include "local_mutex/team_sim.h"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace local_mutex {
namespace {

std::vector<world_sim::Microphone> OmniMicrophones(std::size_t n) {
  return std::vector<world_sim::Microphone>(n, world_sim::Microphone::kOmni);
}

void CheckProbability(double p, const char* name) {
  if (!(p >= 0.0 && p <= 1.0)) {
    throw std::invalid_argument(std::string("team sim: ") + name + " = " + std::to_string(p) +
                                ": expected a probability in [0, 1]");
  }
}

std::unique_ptr<audio_propagation::AcousticModel> MakeAcoustic(const audio_propagation::PropagationModel& model,
                                                               const TeamSimOptions& o, std::size_t robots) {
  if (!o.decode_table) return nullptr;
  std::vector<std::string> names;
  for (std::size_t k = 0; k < robots; ++k) names.push_back("robot_" + std::to_string(k));
  return std::make_unique<audio_propagation::AcousticModel>(model, *o.acoustics, *o.decode_table, names);
}

}  // namespace

void ValidateTeamSimOptions(const TeamSimOptions& o) {
  CheckProbability(o.noise, "noise");
  CheckProbability(o.loss, "loss");
  if (!(o.step > 0.0)) throw std::invalid_argument("team sim: step = " + std::to_string(o.step) + ": expected > 0 s");
  audio_propagation::ValidateOptions(o.channel);
  if (static_cast<bool>(o.decode_table) != o.acoustics.has_value()) {
    throw std::invalid_argument(std::string("team sim: the acoustic channel needs both a decode table and acoustics; got ") +
                                (o.decode_table ? "no acoustics" : "no decode table"));
  }
}

TeamSim::TeamSim(const audio_propagation::PropagationModel& model, std::vector<TeamRobot> robots,
                 const TeamSimOptions& options)
    : robots_(std::move(robots)),
      // Validated before the acoustic model is built from them.
      options_((ValidateTeamSimOptions(options), options)),
      acoustic_(MakeAcoustic(model, options, robots_.size())),
      channel_(model, OmniMicrophones(robots_.size()), options.channel, acoustic_.get()),
      rng_(options.seed) {
  const std::size_t n = robots_.size();
  sending_request_.assign(n, false);
  std::vector<Eigen::Vector2d> positions;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& p = robots_[k].position;
    if (!model.map().IsFreeAt(p)) {
      throw std::invalid_argument("team sim: robot " + std::to_string(robots_[k].id) + " at (" +
                                  std::to_string(p.x()) + ", " + std::to_string(p.y()) +
                                  ") is off the map or in a wall");
    }
    positions.push_back(p);
    channel_.SetPose(k, {p.x(), p.y(), 0.0});
    MutexOptions mo = options_.mutex;
    mo.robot_id = robots_[k].id;
    mo.seed = options_.seed * 7919u + static_cast<std::uint32_t>(k);
    mutexes_.push_back(std::make_unique<LocalMutex>(
        mo, [this, k](const std::vector<std::uint8_t>& packet) { channel_.Send(k, packet); }));
    mutexes_.back()->SetObserver([this, k](const MutexEvent& e) { OnEvent(k, e); });
  }
  // Robots stand still while they want or hold the lock, so who can hear whom is fixed.
  const auto paths = model.Compute(positions, std::vector<bool>(n, true));
  const auto hears = [&](std::size_t from, std::size_t to) {
    if (!paths[from][to].audible) return false;
    if (!acoustic_) return true;
    const auto noise = acoustic_->NoiseAt(positions[to], 0.0, positions);
    return acoustic_->Predict(paths[from][to], positions[to], noise).probability >= 0.5;
  };
  in_range_.assign(n, std::vector<bool>(n, false));
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b) {
      if (a != b) in_range_[a][b] = hears(a, b) || hears(b, a);
    }
  }
  progress_.resize(n);
}

void TeamSim::OnEvent(std::size_t k, const MutexEvent& e) {
  if (e.kind == MutexEvent::Kind::kSent) {
    sending_request_[k] = e.message.type == MessageType::kRequest;
    if (sending_request_[k]) {
      for (std::size_t other = 0; other < mutexes_.size(); ++other) request_copies_.offered += in_range_[k][other];
    }
  }
  if (e.kind == MutexEvent::Kind::kStateChange && e.state == State::kHeld) {
    for (std::size_t other = 0; other < mutexes_.size(); ++other) {
      if (other != k && in_range_[k][other] && mutexes_[other]->state() == State::kHeld) ++violations_;
    }
  }
  if (!options_.record) return;
  RobotEvent re;
  re.robot = k;
  re.event = e;
  if (e.kind == MutexEvent::Kind::kHeard) re.from = sender_;
  events_.push_back(re);
}

void TeamSim::Deliver(const audio_propagation::Reception& rx) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (options_.loss > 0.0 && u(rng_) < options_.loss) {
    ++lost_;
    return;
  }
  const bool packet = rx.kind == audio_propagation::Reception::Kind::kPacket;
  // A whole packet says what it is; noise is the sender's packet being sent (a packet lasts well
  // under the shortest interval between two of a robot's sends).
  const std::optional<Message> message = packet ? Decode(rx.data) : std::nullopt;
  const bool request = packet ? message && message->type == MessageType::kRequest : sending_request_[rx.sender];
  const bool counted = request && in_range_[rx.sender][rx.receiver];
  request_copies_.sounded += counted;
  LocalMutex& m = *mutexes_[rx.receiver];
  if (packet && !(options_.noise > 0.0 && u(rng_) < options_.noise)) {
    request_copies_.heard += counted;
    sender_ = rx.sender;
    m.HearPacket(rx.data, rx.time);
    sender_ = std::numeric_limits<std::size_t>::max();
    return;
  }
  if (packet) ++corrupted_;
  m.HearNoise(rx.time);
}

void TeamSim::FollowDemands(std::size_t k, double now) {
  Progress& p = progress_[k];
  const std::vector<Demand>& demands = robots_[k].demands;
  LocalMutex& m = *mutexes_[k];
  if (p.next >= demands.size()) return;
  const Demand& d = demands[p.next];
  if (!p.wanted) {
    if (now >= d.want_at && m.counters().heard >= d.after_heard && m.Request(now)) {
      p.wanted = true;
      p.wanted_at = now;
    }
    return;
  }
  if (!p.held) {
    if (m.state() != State::kHeld) return;
    p.held = true;
    p.grant = grants_.size();
    grants_.push_back({k, m.request(), p.wanted_at, m.state_since()});
    return;
  }
  if (now >= grants_[p.grant].granted + d.hold) {
    m.Release(now);
    grants_[p.grant].released = now;
    p = Progress{p.next + 1};
  }
}

bool TeamSim::Done() const {
  for (std::size_t k = 0; k < robots_.size(); ++k) {
    if (progress_[k].next < robots_[k].demands.size()) return false;
  }
  return true;
}

std::vector<std::pair<std::size_t, double>> TeamSim::Waiting() const {
  std::vector<std::pair<std::size_t, double>> out;
  for (std::size_t k = 0; k < progress_.size(); ++k) {
    if (progress_[k].wanted && !progress_[k].held) out.emplace_back(k, progress_[k].wanted_at);
  }
  return out;
}

void TeamSim::Run(double until) {
  const std::size_t n = robots_.size();
  while (now_ < until - 1e-9 && !Done()) {
    now_ = std::min(until, now_ + options_.step);
    for (const audio_propagation::Reception& rx : channel_.AdvanceTo(now_).received) Deliver(rx);
    const double now = now_;
    for (std::size_t k = 0; k < n; ++k) {
      FollowDemands(k, now);
      mutexes_[k]->Tick(now);
      FollowDemands(k, now);  // a grant is recorded the moment it happens
    }
  }
}

}  // namespace local_mutex
