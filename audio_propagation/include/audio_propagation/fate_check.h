#pragma once

// Whether the simulated channel's links keep their fate (ChannelOptions::link_fate) as real ones
// do (audio_channel_validate --static-pairs): pairs of places whose model probability lies in
// 20-80 %, each sending a run of packets through the acoustic channel. Standing still, a real
// link delivers nearly all of them or nearly none; moving (the listener a step farther than the
// fate distance before each packet), delivery follows the model's probability. No ROS.
//
// Static pairs are run twice. In steady noise (every duty-cycled source of the world held on) they
// are what the measured rooms' cases are, a link under one condition, and should be all or
// nothing. With the sources on their duty cycles a link near its margin delivers while a radio
// is off and fails while it plays, as a real one would: the held draw decides each packet
// against that packet's own probability. Such pairs deliver in between, and count as undecided.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/channel_validation.h"
#include "audio_propagation/propagation_model.h"
#include "nava_modem/modem_profile.h"

namespace audio_propagation {

struct FateCheckOptions {
  nava_modem::Profile profile = nava_modem::Profile::kNava;
  int pairs = 100;     // of each kind, static and moving
  int packets = 30;    // per pair
  std::uint32_t seed = 1;
  bool link_fate = true;
  double fate_distance = 0.075;  // m (ChannelOptions::fate_distance)
  double min_probability = 0.2, max_probability = 0.8;  // the pairs that count
  double clearance = 0.3;        // m from walls
  double min_separation = 0.5;   // m between the two
  int max_draws = 100000;        // places drawn before giving up on finding the pairs
};

// Throws std::invalid_argument naming the field and its value: pairs and packets at least 1,
// fate_distance above 0, 0 <= min_probability < max_probability <= 1, clearance and
// min_separation at least 0, max_draws at least pairs.
void ValidateOptions(const FateCheckOptions& options);

struct FateCheckResult {
  int static_pairs = 0;           // in steady noise (the world's sources held on)
  int static_decided = 0;         // of them, delivering under 10 % or over 90 % of their packets
  int cycling_pairs = 0;          // static, the world's sources on their duty cycles
  int cycling_decided = 0;        // of them, delivering under 10 % or over 90 % of their packets
  int moving_pairs = 0;
  double moving_delivered = 0.0;  // mean share of packets decoded
  double moving_probability = 0.0;  // mean model probability over the same packets
  int draws = 0;                  // places drawn in all
};

// The pairs, drawn (deterministic for the seed) in the free space connected to the world's
// robots, each judged through its own run of the channel (the world's robots at rest plus the
// two of the pair, kValidationSender and kValidationListener, with the profile's MAC timing).
// Fewer pairs than asked when max_draws runs out.
FateCheckResult CheckLinkFate(const PropagationModel& propagation, const world_sim::Acoustics& acoustics,
                              const DecodeTable& table, const std::vector<std::string>& world_robots,
                              const std::vector<Eigen::Vector2d>& resting, const FateCheckOptions& options);

}  // namespace audio_propagation
