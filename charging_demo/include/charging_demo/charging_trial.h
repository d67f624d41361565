#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/audio_channel.h"
#include "audio_propagation/propagation_model.h"
#include "charging_demo/charging_controller.h"
#include "grid/occupancy_map.h"
#include "local_mutex/mutex_options.h"
#include "world_sim/world.h"
#include "world_sim/world_config.h"

namespace charging_demo {

struct ChargingTrialOptions {
  double duration = 7200.0;       // s of simulated time
  double control_period = 0.1;    // s between controller and lock updates
  double battery_period = 10.0;   // s between battery samples kept for the timeline
  ControllerOptions controller;   // charger ids and seed are set per robot
  local_mutex::MutexOptions mutex;  // robot ids (index + 1) and seeds are set per robot
  audio_propagation::ChannelOptions channel;
  // Set: the acoustic channel model with this decode table and the world's acoustics section
  // (which it must have); unset: the thesis's hearing threshold.
  std::shared_ptr<const audio_propagation::DecodeTable> decode_table;
  world_sim::WorldOptions world;
  std::uint32_t seed = 1;         // the world's, the channel's and (offset) each robot's
};

void ValidateOptions(const ChargingTrialOptions& options);

// A stretch of time one robot spent in one phase of the behaviour.
struct PhaseSpan {
  Phase phase = Phase::kDuty;
  double start = 0.0, end = 0.0;  // s since the start of the trial
};

struct RobotRecord {
  std::uint64_t charges = 0;    // dockings that charged
  std::uint64_t give_ups = 0;   // lock requests withdrawn after lock_timeout
  std::uint64_t redocks = 0;    // dockings backed out of after dock_timeout
  std::uint64_t retraces = 0;   // approaches that went back along the trail
  std::uint64_t wall_loops = 0;  // loops and stalls broken while following walls in a search
  bool flat = false;            // the battery ran empty at some time
  double min_battery = 1.0;
  std::vector<double> waits;    // s from reaching the waiting point to docking, per charge
  std::vector<double> seeks;    // s from battery low to reaching a waiting point
  std::vector<PhaseSpan> phases;
  std::vector<std::pair<double, double>> battery;  // (s, level) every battery_period
  local_mutex::MutexCounters lock;
};

struct ChargingTrialResult {
  double duration = 0.0;
  // Times two or more robots came to be docked at one charger at once (must stay 0).
  std::uint64_t double_dockings = 0;
  std::vector<double> charger_busy;  // s each charger had a robot docked
  std::vector<RobotRecord> robots;
  int collisions = 0;
  std::uint64_t packets_sent = 0;     // lock messages that went on the air
  std::uint64_t queue_overflows = 0;  // lock messages refused by a full link queue

  std::uint64_t charges() const;
  std::size_t flat_robots() const;
  // Docked time over chargers x duration.
  double utilisation() const;
  double mean_wait() const;  // s over every charge; NaN without one
};

// One charging trial in process: the world_sim core (batteries drain, chargers charge), the
// simulated audio channel, and per robot a ChargingController with a LocalMutex on that
// channel, stepped together for `duration`. Watches every charger for double docking.
// `config` must pass ValidateChargingWorld; `model` must be built on `map`. Deterministic for
// the same inputs. Throws std::invalid_argument for impossible options.
ChargingTrialResult RunChargingTrial(const grid::OccupancyMap& map, const world_sim::WorldConfig& config,
                                     const audio_propagation::PropagationModel& model,
                                     const ChargingTrialOptions& options);

}  // namespace charging_demo
