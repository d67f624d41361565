#pragma once

#include <cstdint>
#include <vector>

#include <memory>

#include "audio_propagation/audio_channel.h"
#include "audio_propagation/decode_table.h"
#include "audio_propagation/propagation_model.h"
#include "grid/occupancy_map.h"
#include "sounds_good_explorer/explorer.h"
#include "world_sim/world.h"
#include "world_sim/world_config.h"

namespace sounds_good_explorer {

struct TrialOptions {
  ListenMode mode = ListenMode::kBidirectional;  // every robot's; the microphones follow it
  int jobs = 20;                 // team jobs that end the trial
  double time_cap = 20000.0;     // s of simulated time; a trial not done by then is censored
  double control_period = 0.1;   // s between controller updates
  ExplorerOptions explorer;      // mode and seed are set per robot from the fields here
  audio_propagation::ChannelOptions channel;
  // Set: the acoustic channel model with this decode table and the world's acoustics section
  // (which it then must have); null: the threshold model.
  std::shared_ptr<const audio_propagation::DecodeTable> decode_table;
  world_sim::WorldOptions world;
  std::uint32_t seed = 1;        // the world's, the channel's and (offset) each controller's
};

void ValidateOptions(const TrialOptions& options);

struct JobRecord {
  std::size_t robot = 0;
  std::uint32_t marker = 0;
  double time = 0.0;  // s since the start of the trial
};

struct TrialResult {
  double time = 0.0;      // s to the last job, or the cap when censored
  bool censored = false;  // the team did not finish within time_cap
  std::vector<JobRecord> jobs;
  int collisions = 0;
  std::uint64_t stuck = 0;           // times a robot backed off, summed over the team
  std::uint64_t packets_sent = 0;    // announcements that went on the air
  std::uint64_t packets_heard = 0;   // announcements received whole
  std::uint64_t queue_overflows = 0; // announcements refused by a full link queue
};

// One Sounds Good trial in process: the world_sim core, the simulated audio channel and one
// Explorer per robot, stepped together until the team has done `jobs` jobs or the cap.
// `model` must be built on `map` with the hearing range of the experiment. Deterministic for
// the same inputs. Throws std::invalid_argument for impossible options (zero jobs, ...).
TrialResult RunTeamTrial(const grid::OccupancyMap& map, const world_sim::WorldConfig& config,
                         const audio_propagation::PropagationModel& model,
                         const TrialOptions& options);

}  // namespace sounds_good_explorer
