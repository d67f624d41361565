#include "charging_demo/charging_world.h"

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "grid/input_error.h"
#include "grid/option_checks.h"
#include "grid/reachability.h"

namespace charging_demo {

namespace {

// Draws per item before giving up: plenty when the map has room, bounded when it has not.
constexpr int kAttempts = 2000;
// The lock's robot ids are one byte, 0 reserved.
constexpr int kMaxRobots = 255;

}  // namespace

void ValidateOptions(const ChargingWorldOptions& o) {
  if (o.chargers < 1)
    throw std::invalid_argument("chargers must be at least 1, got " + std::to_string(o.chargers));
  if (o.robots < 1 || o.robots > kMaxRobots)
    throw std::invalid_argument("robots must be within 1.." + std::to_string(kMaxRobots) + ", got " +
                                std::to_string(o.robots));
  if (!(o.min_battery > 0.0 && o.min_battery <= 1.0))
    throw std::invalid_argument("initial battery minimum must be within (0, 1], got " +
                                std::to_string(o.min_battery));
  grid::RequireAtLeast("charger_clearance (m)", o.charger_clearance, 0.0);
  grid::RequireAtLeast("charger_spacing (m)", o.charger_spacing, 0.0);
  grid::RequireAtLeast("robot_clearance (m)", o.robot_clearance, 0.0);
  grid::RequireAtLeast("margin (m)", o.margin, 0.0);
}

world_sim::WorldConfig RandomChargingWorld(const grid::OccupancyMap& map, const std::string& map_file,
                                           const world_sim::RobotModel& model,
                                           const ChargingWorldOptions& o, std::mt19937& rng) {
  ValidateOptions(o);
  const grid::Reachability robot_room(map, model.radius + o.margin);
  const grid::Reachability charger_room(map, o.charger_clearance);
  const int region = robot_room.largest();
  if (region == 0) throw std::invalid_argument("no room for a robot anywhere on " + map_file);

  world_sim::WorldConfig config;
  config.map_file = map_file;
  config.model = model;
  std::vector<Eigen::Vector2d> chargers;
  for (int c = 0; c < o.chargers; ++c) {
    bool placed = false;
    for (int attempt = 0; attempt < kAttempts && !placed; ++attempt) {
      if (charger_room.largest() == 0) break;
      const Eigen::Vector2d p = charger_room.Sample(charger_room.largest(), rng);
      if (robot_room.Region(p) != region) continue;
      placed = true;
      for (const Eigen::Vector2d& q : chargers) placed = placed && (p - q).norm() >= o.charger_spacing;
      if (placed) chargers.push_back(p);
    }
    if (!placed)
      throw std::invalid_argument("cannot place " + std::to_string(o.chargers) + " chargers " +
                                  std::to_string(o.charger_spacing) + " m apart with " +
                                  std::to_string(o.charger_clearance) + " m clear of walls on " +
                                  map_file + " (placed " + std::to_string(c) + ")");
    world_sim::ChargerSpec spec;
    spec.pose = {chargers.back().x(), chargers.back().y(), 0.0};
    spec.marker = o.first_marker + static_cast<std::uint32_t>(c);
    config.chargers.push_back(spec);
  }
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), level(o.min_battery, 1.0);
  std::vector<Eigen::Vector2d> robots;
  for (int k = 0; k < o.robots; ++k) {
    bool placed = false;
    for (int attempt = 0; attempt < kAttempts && !placed; ++attempt) {
      const Eigen::Vector2d p = robot_room.Sample(region, rng);
      placed = true;
      for (const Eigen::Vector2d& q : robots) placed = placed && (p - q).norm() > 2.0 * model.radius + o.margin;
      for (const Eigen::Vector2d& q : chargers) placed = placed && (p - q).norm() >= o.robot_clearance;
      if (placed) robots.push_back(p);
    }
    if (!placed)
      throw std::invalid_argument("cannot fit " + std::to_string(o.robots) + " robots on " + map_file +
                                  " (placed " + std::to_string(k) + ")");
    world_sim::RobotSpec spec;
    spec.name = "robot_" + std::to_string(k);
    spec.start = {robots.back().x(), robots.back().y(), yaw(rng)};
    spec.microphone = world_sim::Microphone::kOmni;
    spec.battery = level(rng);
    config.robots.push_back(spec);
  }
  return config;
}

void ValidateChargingWorld(const std::string& file, const world_sim::WorldConfig& config) {
  if (config.chargers.empty())
    throw grid::InputError(file, "chargers", "the charging trial needs at least one charger");
  for (std::size_t c = 0; c < config.chargers.size(); ++c)
    if (!config.chargers[c].marker)
      throw grid::InputError(file, "chargers[" + std::to_string(c) + "].marker",
                             "every charger needs a fiducial marker: robots find chargers by sight");
  if (config.robots.empty()) throw grid::InputError(file, "robots", "expected at least one robot");
  if (config.robots.size() > static_cast<std::size_t>(kMaxRobots))
    throw grid::InputError(file, "robots",
                           "at most " + std::to_string(kMaxRobots) + " robots (the lock's ids are one byte), got " +
                               std::to_string(config.robots.size()));
}

}  // namespace charging_demo
