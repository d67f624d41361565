#include "charging_demo/charging_trial.h"

#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include "charging_demo/charging_world.h"
#include "local_mutex/local_mutex.h"
#include "local_navigation/world_readings.h"

namespace charging_demo {

namespace {

// What one robot's run looks like as it goes, beyond what the controller keeps.
struct Tracker {
  Phase phase = Phase::kDuty;
  double phase_start = 0.0;
  std::optional<double> low_since;   // battery low, not yet at a waiting point
  std::optional<double> wait_since;  // at the waiting point, not yet docked
};

}  // namespace

void ValidateOptions(const ChargingTrialOptions& o) {
  if (!(o.duration > 0.0))
    throw std::invalid_argument("duration must be > 0 s, got " + std::to_string(o.duration));
  if (!(o.control_period > 0.0))
    throw std::invalid_argument("control period must be > 0 s, got " + std::to_string(o.control_period));
  if (!(o.battery_period > 0.0))
    throw std::invalid_argument("battery period must be > 0 s, got " + std::to_string(o.battery_period));
  local_mutex::ValidateMutexOptions(o.mutex);
}

std::uint64_t ChargingTrialResult::charges() const {
  std::uint64_t total = 0;
  for (const RobotRecord& r : robots) total += r.charges;
  return total;
}

std::size_t ChargingTrialResult::flat_robots() const {
  std::size_t total = 0;
  for (const RobotRecord& r : robots) total += r.flat ? 1 : 0;
  return total;
}

double ChargingTrialResult::utilisation() const {
  if (charger_busy.empty() || !(duration > 0.0)) return 0.0;
  return std::accumulate(charger_busy.begin(), charger_busy.end(), 0.0) /
         (duration * static_cast<double>(charger_busy.size()));
}

double ChargingTrialResult::mean_wait() const {
  double sum = 0.0;
  std::size_t n = 0;
  for (const RobotRecord& r : robots) {
    sum = std::accumulate(r.waits.begin(), r.waits.end(), sum);
    n += r.waits.size();
  }
  return n ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

ChargingTrialResult RunChargingTrial(const grid::OccupancyMap& map, const world_sim::WorldConfig& config,
                                     const audio_propagation::PropagationModel& model,
                                     const ChargingTrialOptions& options) {
  ValidateOptions(options);
  ValidateChargingWorld(config.map_file, config);
  world_sim::WorldConfig team = config;
  team.seed = options.seed;
  for (world_sim::RobotSpec& r : team.robots) r.microphone = world_sim::Microphone::kOmni;
  world_sim::World world(map, team, options.world);
  const std::size_t n = team.robots.size();

  audio_propagation::ChannelOptions channel_options = options.channel;
  channel_options.seed = options.seed;
  const std::unique_ptr<audio_propagation::AcousticModel> acoustic =
      audio_propagation::TeamAcousticModel(model, team, options.decode_table);
  audio_propagation::AudioChannel channel(
      model, std::vector<world_sim::Microphone>(n, world_sim::Microphone::kOmni), channel_options, acoustic.get());

  ChargingTrialResult result;
  result.duration = options.duration;
  result.robots.resize(n);
  result.charger_busy.assign(team.chargers.size(), 0.0);

  std::set<std::uint32_t> charger_ids;
  for (const world_sim::ChargerSpec& c : team.chargers) charger_ids.insert(*c.marker);
  std::vector<ChargingController> robots;
  std::vector<std::unique_ptr<local_mutex::LocalMutex>> locks;
  robots.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    ControllerOptions o = options.controller;
    o.charging.chargers = charger_ids;
    o.navigation.planner.robot_radius = team.model.radius;
    o.navigation.motion.max_speed = team.model.max_speed;
    o.navigation.motion.max_turn_rate = team.model.max_turn_rate;
    o.seed = (options.seed * 2654435761u) ^ (0x9E3779B9u * (static_cast<std::uint32_t>(k) + 1u));
    robots.emplace_back(o);
    local_mutex::MutexOptions m = options.mutex;
    m.robot_id = static_cast<int>(k) + 1;
    m.seed = options.seed * 7919u + static_cast<std::uint32_t>(k);
    locks.push_back(std::make_unique<local_mutex::LocalMutex>(
        m, [&channel, &result, k](const std::vector<std::uint8_t>& packet) {
          ++result.packets_sent;
          if (!channel.Send(k, packet)) ++result.queue_overflows;
        }));
  }

  local_navigation::WorldReadings readings(team.model, n);
  std::vector<Tracker> trackers(n);
  std::vector<int> docked_at(team.chargers.size(), 0);
  const std::uint64_t control_every = world_sim::StepsPerPeriod(options.control_period, options.world.step);
  const std::uint64_t battery_every = world_sim::StepsPerPeriod(options.battery_period, options.world.step);
  const double dt = control_every * options.world.step;
  std::vector<ChargerSighting> sightings;

  while (world.elapsed() < options.duration - 1e-9) {
    world.Step();
    const auto& states = world.robots();
    for (std::size_t k = 0; k < n; ++k) {
      RobotRecord& record = result.robots[k];
      record.min_battery = std::min(record.min_battery, states[k].battery);
      if (states[k].battery <= 0.0) record.flat = true;
      if (world.steps() % battery_every == 0) record.battery.emplace_back(world.elapsed(), states[k].battery);
    }
    if (world.steps() % control_every != 0) continue;
    const double now = world.time();
    const double elapsed = world.elapsed();

    // Safety: who is docked where (the truth, not what any robot believes).
    for (std::size_t c = 0; c < team.chargers.size(); ++c) {
      const world_sim::ChargerSpec& charger = team.chargers[c];
      int docked = 0;
      for (const world_sim::RobotState& s : states)
        if ((s.pose.position() - charger.pose.position()).norm() <= charger.radius) ++docked;
      if (docked >= 2 && docked_at[c] < 2) ++result.double_dockings;
      if (docked >= 1) result.charger_busy[c] += dt;
      docked_at[c] = docked;
    }

    for (std::size_t k = 0; k < n; ++k) channel.SetPose(k, states[k].pose);
    for (const audio_propagation::Reception& rx : channel.AdvanceTo(now).received) {
      if (rx.kind == audio_propagation::Reception::Kind::kPacket) locks[rx.receiver]->HearPacket(rx.data, now);
      else locks[rx.receiver]->HearNoise(now);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const world_sim::RobotState& s = states[k];
      // A flat robot is dead: its controller and its lock stop (a held lock goes quiet, and
      // the others take it once their grab timers run out).
      if (result.robots[k].flat) continue;
      ChargingController& robot = robots[k];
      const local_navigation::WorldReadings::Fresh fresh = readings.Take(k, s);
      if (fresh.odom) robot.OnOdometry(s.odom, now);
      if (fresh.ranges) robot.OnRanges(readings.ranges(), readings.reach(), now);
      if (fresh.fiducials) {
        sightings.clear();
        for (const world_sim::FiducialSighting& f : s.fiducials) sightings.push_back({f.id, f.range, f.bearing});
        robot.OnSightings(sightings);
      }
      robot.OnBattery(s.battery, s.docked);
      local_mutex::LocalMutex& lock = *locks[k];
      lock.Tick(now);
      const ControllerOutput out = robot.Update(lock.state(), now);
      if (out.want_lock && lock.state() == local_mutex::State::kReleased) lock.Request(now);
      if (!out.want_lock && lock.state() != local_mutex::State::kReleased) lock.Release(now);
      world.SetCommand(k, out.v, out.w);

      // The record: phases, and the times from low battery to the waiting point and on to docking.
      Tracker& t = trackers[k];
      RobotRecord& record = result.robots[k];
      const Phase phase = robot.behaviour().phase();
      if (phase == t.phase) continue;
      record.phases.push_back({t.phase, t.phase_start, elapsed});
      if (t.phase == Phase::kDuty) t.low_since = elapsed;
      if (phase == Phase::kWait && !t.wait_since) {
        t.wait_since = elapsed;
        if (t.low_since) record.seeks.push_back(elapsed - *t.low_since);
        t.low_since.reset();
      }
      if (phase == Phase::kCharge && t.wait_since) {
        record.waits.push_back(elapsed - *t.wait_since);
        t.wait_since.reset();
      }
      if (phase == Phase::kSeek) t.wait_since.reset();  // gave up on that charger
      t.phase = phase;
      t.phase_start = elapsed;
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    RobotRecord& record = result.robots[k];
    record.phases.push_back({trackers[k].phase, trackers[k].phase_start, world.elapsed()});
    record.charges = robots[k].behaviour().charges();
    record.give_ups = robots[k].behaviour().give_ups();
    record.redocks = robots[k].behaviour().redocks();
    record.retraces = robots[k].retraces();
    record.wall_loops = robots[k].wall_loops();
    record.lock = locks[k]->counters();
  }
  result.collisions = world.TotalCollisions();
  return result;
}

}  // namespace charging_demo
