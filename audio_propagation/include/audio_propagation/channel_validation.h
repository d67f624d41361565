#pragma once

// Validation of the `acoustic` channel model against the real receiver (audio_channel_validate):
// random links in a world with acoustics, each judged twice, by the model (AcousticModel::Predict
// with the noise of that moment, as the channel judges a packet) and by the profile's real
// receiver decoding the link's packets rendered at the listener by the scene renderer
// (scene_render.h): one link is one small scene. No ROS.
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/scene_render.h"
#include "nava_modem/modem_profile.h"

namespace audio_propagation {

// The propagation options the validation tools use: the robots' speaker level and every path in
// a map of `map_span` metres (width plus height), with no hearing threshold: the model and the
// renderer judge far links themselves. (The simulated channel drops links beyond its
// PropagationModel's hearing distance, ~threshold_db; see ValidationLink::beyond_hearing.)
PropagationOptions ValidationPropagation(double map_span, int threads);

// Where links may stand: free points at least `clearance` m from walls, in the free space that is
// connected to `seed` (a robot's place: not outside the building), or anywhere free without one.
class FreePoints {
 public:
  FreePoints(const grid::OccupancyMap& map, double clearance, const Eigen::Vector2d* seed);
  // A point uniformly over those cells (and within its cell). Throws std::runtime_error when
  // there is none.
  Eigen::Vector2d Draw(std::mt19937& rng) const;
  std::size_t size() const { return cells_.size(); }

 private:
  const grid::OccupancyMap& map_;
  double clearance_;
  std::vector<Eigen::Vector2i> cells_;  // free and connected to the seed
};

struct ValidationOptions {
  nava_modem::Profile profile = nava_modem::Profile::kNava;
  int links = 300;
  int packets = 4;          // per link
  std::uint32_t seed = 1;
  int threads = 2;
  double clearance = 0.3;   // m from walls
  double min_separation = 0.5;  // m between sender and listener
  double sample_rate = 48000.0;
  std::vector<float> speech;  // at sample_rate, for worlds with speech
  // For a table measured over measured rooms (SceneRenderOptions::measured_rooms).
  std::shared_ptr<const nava_modem::MovedRooms> measured_rooms;
  // The simulated channel's hearing distance (m): links longer are flagged (beyond_hearing).
  double channel_hearing_distance = 0.0;  // 0: not flagged
};

// Throws std::invalid_argument naming the field and its value: links, packets and threads at
// least 1, clearance, min_separation and channel_hearing_distance at least 0, a sample rate the
// modems run at (nava_modem::ValidateSampleRate).
void ValidateOptions(const ValidationOptions& options);

// One packet of a link, judged twice.
struct JudgedPacket {
  double probability = 0.0;  // the model's
  bool decoded = false;      // by the real receiver
  double snr_db = 0.0;       // the model's
  Interference kind = Interference::kPink;  // the model's loudest disturbance
  // The rendered noise's level during the packet minus the level of the disturbances the model
  // counted, unweighted (dB; the packet's own level agrees by construction): far from 0 where
  // a noise source switched during the packet or speech paused or burst.
  double noise_gap_db = 0.0;
};

struct ValidationLink {
  Eigen::Vector2d sender, listener;
  double time = 0.0;         // s, when the first packet is sent (the noise sources' duty state)
  bool reachable = false;
  double path_length = 0.0;  // m
  int corners = 0;
  double model = 0.0;        // mean decode probability over the packets
  int decoded = 0;           // of `packets`, by the real receiver
  int packets = 0;
  // The first packet's figures (the others differ only by the noise sources' duty state).
  LinkPrediction prediction;
  std::vector<JudgedPacket> judged;  // each packet, when there is a path
  bool beyond_hearing = false;
};

struct DistanceBin {
  double low = 0.0, high = 0.0;  // m; high may be infinite
  int links = 0;
  double mean_length = 0.0;            // m, over its links that have a path
  double model = 0.0, rendered = 0.0;  // % of packets
};

// The team the validation renders: the world's robots at rest plus the two a link moves.
constexpr const char* kValidationSender = "validation_sender";
constexpr const char* kValidationListener = "validation_listener";

// Draws the links (deterministic for the seed) and judges each on `threads` threads (each with
// its own model, renderer and receiver; the result does not depend on the thread count).
// `world_robots` and `resting` are the world's team; `progress`, if given, is called after each
// link with the number done. Throws std::invalid_argument for impossible options.
std::vector<ValidationLink> ValidateLinks(const PropagationModel& propagation, const world_sim::Acoustics& acoustics,
                                          const DecodeTable& table, const std::vector<std::string>& world_robots,
                                          const std::vector<Eigen::Vector2d>& resting, const ValidationOptions& options,
                                          const std::function<void(int)>& progress = {});

// Bins links by path length at `edges` (ascending, the last bin open-ended), merging a bin of
// fewer than `min_links` links into its neighbour (left to right; a short last bin into the one
// before). Empty bins are left out.
std::vector<DistanceBin> BinByLength(const std::vector<ValidationLink>& links, const std::vector<double>& edges,
                                     int min_links);
constexpr double kDefaultEdges[] = {0.0, 3.0, 6.0, 10.0, 15.0, 20.0, 30.0};

// max |model - rendered| over the bins, in percentage points.
double Agreement(const std::vector<DistanceBin>& bins);

}  // namespace audio_propagation
