#include "audio_propagation/fate_check.h"

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

#include "audio_propagation/audio_channel.h"
#include "grid/option_checks.h"

namespace audio_propagation {
namespace {

// Long enough for a packet of either profile, its CSMA back-off and its travel, in 50 ms steps.
constexpr double kPacketWait = 4.0;
constexpr double kStep = 0.05;

// The model's probability for a packet from `a` to `b` at time `t`, the world's robots at rest
// (no other packet in the air).
double Probability(const PropagationModel& propagation, const AcousticModel& model, std::vector<Eigen::Vector2d> at,
                   const Eigen::Vector2d& a, const Eigen::Vector2d& b, double t) {
  at.push_back(a);
  at.push_back(b);
  return model.Predict(propagation.Path(a, b), b, model.NoiseAt(b, t, at)).probability;
}

// One pair's channel: the world's robots at rest and the two of the pair (`model` built for the
// world's robots, kValidationSender and kValidationListener).
class PairChannel {
 public:
  PairChannel(const PropagationModel& propagation, const AcousticModel& model, const std::vector<Eigen::Vector2d>& resting,
              const FateCheckOptions& o, std::uint32_t seed)
      : resting_(resting) {
    ChannelOptions c;
    c.seed = seed;
    c.link_fate = o.link_fate;
    c.fate_distance = o.fate_distance;
    nava_modem::UseProfileTiming(o.profile, nava_modem::ModemOptions{}, c.mac);
    channel_ = std::make_unique<AudioChannel>(propagation, std::vector<world_sim::Microphone>(resting.size() + 2, world_sim::Microphone::kOmni),
                                              c, &model);
    for (std::size_t k = 0; k < resting.size(); ++k) channel_->SetPose(k, {resting[k].x(), resting[k].y(), 0.0});
  }
  std::size_t sender() const { return resting_.size(); }
  std::size_t listener() const { return resting_.size() + 1; }
  void Place(std::size_t robot, const Eigen::Vector2d& at) { channel_->SetPose(robot, {at.x(), at.y(), 0.0}); }
  // Lets the MACs calibrate on the room's noise, as a robot does when it starts.
  void Calibrate(double seconds) { Run(seconds); }
  double time() const { return channel_->time(); }
  // Sends one packet from the sender; true when the listener decoded it.
  bool Packet(int k) {
    channel_->Send(sender(), {0xFA, 0x7E, static_cast<std::uint8_t>(k >> 8), static_cast<std::uint8_t>(k)});
    bool decoded = false;
    const double end = channel_->time() + kPacketWait;
    while (channel_->time() < end - 1e-9) {
      for (const Reception& r : channel_->AdvanceTo(channel_->time() + kStep).received) {
        decoded = decoded || (r.receiver == listener() && r.sender == sender() && r.kind == Reception::Kind::kPacket);
      }
      if (channel_->Idle()) break;
    }
    return decoded;
  }

 private:
  void Run(double seconds) {
    const double end = channel_->time() + seconds;
    while (channel_->time() < end - 1e-9) channel_->AdvanceTo(channel_->time() + kStep);
  }
  std::vector<Eigen::Vector2d> resting_;
  std::unique_ptr<AudioChannel> channel_;
};

}  // namespace

void ValidateOptions(const FateCheckOptions& o) {
  grid::RequireAtLeast("fate check pairs", o.pairs, 1);
  grid::RequireAtLeast("fate check packets", o.packets, 1);
  grid::RequireAbove("fate check fate_distance (m)", o.fate_distance, 0.0);
  if (!(o.min_probability >= 0.0 && o.min_probability < o.max_probability && o.max_probability <= 1.0)) {
    throw std::invalid_argument("fate check probabilities must satisfy 0 <= min < max <= 1, got " +
                                std::to_string(o.min_probability) + " and " + std::to_string(o.max_probability));
  }
  grid::RequireAtLeast("fate check clearance (m)", o.clearance, 0.0);
  grid::RequireAtLeast("fate check min_separation (m)", o.min_separation, 0.0);
  grid::RequireAtLeast("fate check max_draws", o.max_draws, o.pairs);
}

namespace {

// The world's noise with every duty-cycled source sounding all the time.
world_sim::Acoustics HeldOn(world_sim::Acoustics acoustics) {
  for (world_sim::NoiseSourceSpec& source : acoustics.noise_sources) source.duty = 1.0;
  return acoustics;
}

// What one kind of pair (static or moving) gave.
struct PairRuns {
  int pairs = 0;
  int decided = 0;                 // static: delivering under 10 % or over 90 % of their packets
  double delivered_sum = 0.0;      // moving: the pairs' shares of packets decoded
  double probability_sum = 0.0;   // moving: the pairs' mean model probabilities
};

// Draws pairs of places at model probability min..max_probability and runs each through its own
// channel: `moving` steps the listener twice the fate distance before every packet but the first.
PairRuns RunPairs(const PropagationModel& propagation, const world_sim::Acoustics& acoustics, const DecodeTable& table,
                  const std::vector<std::string>& names, const std::vector<Eigen::Vector2d>& resting,
                  const FreePoints& points, const FateCheckOptions& o, bool moving, std::mt19937& rng, int& draws) {
  const AcousticModel model(propagation, acoustics, table, names);
  const nava_modem::MacOptions calibration;
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  PairRuns runs;
  while (runs.pairs < o.pairs && draws < o.max_draws) {
    ++draws;
    const Eigen::Vector2d a = points.Draw(rng), b = points.Draw(rng);
    if ((a - b).norm() < o.min_separation || !propagation.Path(a, b).reachable) continue;
    // Judged as the pair's packets will be, after the MACs' calibration; only then is a
    // channel run for the pair.
    const double p = Probability(propagation, model, resting, a, b, calibration.calibration_time);
    if (p < o.min_probability || p > o.max_probability) continue;
    PairChannel pair(propagation, model, resting, o, o.seed * 7919u + static_cast<std::uint32_t>(draws));
    pair.Place(pair.sender(), a);
    pair.Place(pair.listener(), b);
    pair.Calibrate(calibration.calibration_time);
    ++runs.pairs;
    int delivered = 0;
    double probability = 0.0;
    Eigen::Vector2d at = b;
    for (int k = 0; k < o.packets; ++k) {
      if (moving && k > 0) {
        // A step of twice the fate distance, to a free place from which the sender is heard.
        for (int attempt = 0; attempt < 16; ++attempt) {
          const double t = angle(rng);
          const Eigen::Vector2d next = at + 2.0 * o.fate_distance * Eigen::Vector2d(std::cos(t), std::sin(t));
          if (propagation.map().IsFreeAt(next) && propagation.Path(a, next).reachable) {
            at = next;
            break;
          }
        }
        pair.Place(pair.listener(), at);
      }
      probability += Probability(propagation, model, resting, a, at, pair.time());
      delivered += pair.Packet(k);
    }
    runs.decided += delivered < 0.1 * o.packets || delivered > 0.9 * o.packets;
    runs.delivered_sum += static_cast<double>(delivered) / o.packets;
    runs.probability_sum += probability / o.packets;
  }
  return runs;
}

}  // namespace

FateCheckResult CheckLinkFate(const PropagationModel& propagation, const world_sim::Acoustics& acoustics,
                              const DecodeTable& table, const std::vector<std::string>& world_robots,
                              const std::vector<Eigen::Vector2d>& resting, const FateCheckOptions& o) {
  ValidateOptions(o);
  const FreePoints points(propagation.map(), o.clearance, resting.empty() ? nullptr : &resting.front());
  std::mt19937 rng(o.seed);
  std::vector<std::string> names = world_robots;
  names.push_back(kValidationSender);
  names.push_back(kValidationListener);
  FateCheckResult result;
  const PairRuns steady =
      RunPairs(propagation, HeldOn(acoustics), table, names, resting, points, o, false, rng, result.draws);
  result.static_pairs = steady.pairs;
  result.static_decided = steady.decided;
  const PairRuns cycling = RunPairs(propagation, acoustics, table, names, resting, points, o, false, rng, result.draws);
  result.cycling_pairs = cycling.pairs;
  result.cycling_decided = cycling.decided;
  const PairRuns moving = RunPairs(propagation, acoustics, table, names, resting, points, o, true, rng, result.draws);
  result.moving_pairs = moving.pairs;
  result.moving_delivered = moving.pairs ? moving.delivered_sum / moving.pairs : 0.0;
  result.moving_probability = moving.pairs ? moving.probability_sum / moving.pairs : 0.0;
  return result;
}

}  // namespace audio_propagation
