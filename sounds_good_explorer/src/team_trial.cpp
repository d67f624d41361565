#include "sounds_good_explorer/team_trial.h"

#include <stdexcept>
#include <string>

#include "local_navigation/world_readings.h"

namespace sounds_good_explorer {

namespace {

world_sim::Microphone MicrophoneFor(ListenMode mode) {
  switch (mode) {
    case ListenMode::kOmni: return world_sim::Microphone::kOmni;
    case ListenMode::kBidirectional: return world_sim::Microphone::kBidirectional;
    case ListenMode::kNone: return world_sim::Microphone::kNone;
  }
  return world_sim::Microphone::kNone;
}

}  // namespace

void ValidateOptions(const TrialOptions& o) {
  if (o.jobs < 1)
    throw std::invalid_argument("jobs must be at least 1, got " + std::to_string(o.jobs));
  if (!(o.time_cap > 0.0))
    throw std::invalid_argument("time cap must be > 0 s, got " + std::to_string(o.time_cap));
  if (!(o.control_period > 0.0))
    throw std::invalid_argument("control period must be > 0 s, got " +
                                std::to_string(o.control_period));
  ValidateOptions(o.explorer);
}

TrialResult RunTeamTrial(const grid::OccupancyMap& map, const world_sim::WorldConfig& config,
                         const audio_propagation::PropagationModel& model,
                         const TrialOptions& options) {
  ValidateOptions(options);
  if (config.robots.empty()) throw std::invalid_argument("a trial needs at least one robot");
  world_sim::WorldConfig team = config;
  team.seed = options.seed;
  for (world_sim::RobotSpec& r : team.robots) r.microphone = MicrophoneFor(options.mode);
  world_sim::World world(map, team, options.world);

  const std::size_t n = team.robots.size();
  audio_propagation::ChannelOptions channel_options = options.channel;
  channel_options.seed = options.seed;
  const std::unique_ptr<audio_propagation::AcousticModel> acoustic =
      audio_propagation::TeamAcousticModel(model, team, options.decode_table);
  audio_propagation::AudioChannel channel(
      model, std::vector<world_sim::Microphone>(n, MicrophoneFor(options.mode)), channel_options, acoustic.get());

  std::vector<Explorer> robots;
  robots.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    ExplorerOptions o = options.explorer;
    o.mode = options.mode;
    // The controller fits the robot it drives.
    o.planner.robot_radius = team.model.radius;
    o.motion.max_speed = team.model.max_speed;
    o.motion.max_turn_rate = team.model.max_turn_rate;
    // A seed of its own, unlike world_sim's per-robot seeds (world seed + index).
    o.seed = (options.seed * 2654435761u) ^ (0x9E3779B9u * (static_cast<std::uint32_t>(k) + 1u));
    robots.emplace_back(o);
  }
  local_navigation::WorldReadings readings(team.model, n);
  const std::uint64_t control_every =
      world_sim::StepsPerPeriod(options.control_period, options.world.step);
  TrialResult result;
  std::vector<MarkerSighting> sightings;
  while (static_cast<int>(result.jobs.size()) < options.jobs && world.elapsed() < options.time_cap) {
    world.Step();
    if (world.steps() % control_every != 0) continue;
    const double now = world.time();
    const auto& states = world.robots();
    for (std::size_t k = 0; k < n; ++k) channel.SetPose(k, states[k].pose);
    const audio_propagation::AudioChannel::Events events = channel.AdvanceTo(now);
    result.packets_sent += events.started.size();
    for (const audio_propagation::Reception& rx : events.received) {
      if (rx.kind != audio_propagation::Reception::Kind::kPacket) continue;
      ++result.packets_heard;
      robots[rx.receiver].OnHeard(rx.data, rx.level_db, rx.direction, now);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const world_sim::RobotState& s = states[k];
      Explorer& robot = robots[k];
      const local_navigation::WorldReadings::Fresh fresh = readings.Take(k, s);
      if (fresh.odom) robot.OnOdometry(s.odom, now);
      if (fresh.ranges) robot.OnRanges(readings.ranges(), readings.reach(), now);
      if (fresh.fiducials) {
        sightings.clear();
        for (const world_sim::FiducialSighting& f : s.fiducials)
          sightings.push_back({f.id, f.range, f.bearing});
        robot.OnSightings(sightings, now);
      }
      const ExplorerOutput out = robot.Update(now);
      world.SetCommand(k, out.v, out.w);
      for (const auto& packet : out.packets)
        if (!channel.Send(k, {packet.begin(), packet.end()})) ++result.queue_overflows;
      if (out.job) result.jobs.push_back({k, out.job->marker, world.elapsed()});
    }
  }
  result.censored = static_cast<int>(result.jobs.size()) < options.jobs;
  result.time = result.censored ? options.time_cap : result.jobs.back().time;
  result.collisions = world.TotalCollisions();
  for (const Explorer& r : robots) result.stuck += r.stuck_count();
  return result;
}

}  // namespace sounds_good_explorer
