#include "sounds_good_explorer/configurations.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "grid/input_error.h"
#include "grid/option_checks.h"
#include "grid/reachability.h"
#include "world_sim/world_file.h"

namespace sounds_good_explorer {

namespace {

std::string Where(double x, double y) {
  std::ostringstream s;
  s.precision(3);
  s << "(" << x << ", " << y << ")";
  return s.str();
}

}  // namespace

void ValidateOptions(const ConfigurationOptions& o) {
  if (o.robots < 1)
    throw std::invalid_argument("a configuration needs at least 1 robot, got " + std::to_string(o.robots));
  if (o.source == o.sink)
    throw std::invalid_argument("configuration source and sink must be different markers, both are " +
                                std::to_string(o.source));
  grid::RequireAtLeast("configuration margin (m)", o.margin, 0.0);
  grid::RequireAtLeast("configuration min_marker_separation (m)", o.min_marker_separation, 0.0);
}

world_sim::WorldConfig RandomConfiguration(const grid::OccupancyMap& map,
                                           const std::string& map_file,
                                           const world_sim::RobotModel& model,
                                           const ConfigurationOptions& options, std::mt19937& rng) {
  ValidateOptions(options);
  // A cell's centre stands for every point in it (and a draw is jittered within the cell), so
  // keep a cell's width more room: the world's own overlap test then never refuses a draw.
  const grid::Reachability room(map, model.radius + options.margin + map.resolution());
  const int region = room.largest();
  world_sim::WorldConfig config;
  config.map_file = map_file;
  config.model = model;
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI);
  // Rejection sampling: the region is most of the map, so a few draws suffice; the bound
  // turns an impossible request (too many robots for the room) into an error.
  const int max_draws = 100000;
  int draws = 0;
  auto draw = [&]() {
    if (++draws > max_draws)
      throw std::invalid_argument("cannot place " + std::to_string(options.robots) +
                                  " robots and two markers on " + map_file);
    return room.Sample(region, rng);
  };
  while (static_cast<int>(config.robots.size()) < options.robots) {
    const Eigen::Vector2d p = draw();
    const bool overlaps = std::any_of(config.robots.begin(), config.robots.end(), [&](const auto& r) {
      return (r.start.position() - p).norm() < 2.0 * model.radius + options.margin;
    });
    if (overlaps) continue;
    world_sim::RobotSpec r;
    r.name = "robot_" + std::to_string(config.robots.size());
    r.start = {p.x(), p.y(), yaw(rng)};
    config.robots.push_back(r);
  }
  const Eigen::Vector2d source = draw();
  Eigen::Vector2d sink = draw();
  while ((sink - source).norm() < options.min_marker_separation) sink = draw();
  config.markers = {{options.source, source.x(), source.y()}, {options.sink, sink.x(), sink.y()}};
  return config;
}

void ValidateConfiguration(const std::string& file, const world_sim::WorldConfig& config,
                           const grid::OccupancyMap& map, std::uint32_t source, std::uint32_t sink) {
  world_sim::ValidateWorld(file, config, map);
  if (config.robots.empty()) throw grid::InputError(file, "robots", "expected at least one robot");
  const grid::Reachability room(map, config.model.radius);
  const world_sim::RobotSpec& first = config.robots.front();
  const int region = room.Region(first.start.position());
  if (region == 0)
    throw grid::InputError(file, "robots[0].pose",
                           "robot '" + first.name + "' at " + Where(first.start.x, first.start.y) +
                               " has no room to move (a wall is closer than its radius)");
  for (std::size_t k = 1; k < config.robots.size(); ++k) {
    const world_sim::RobotSpec& r = config.robots[k];
    if (room.Region(r.start.position()) != region)
      throw grid::InputError(file, "robots[" + std::to_string(k) + "].pose",
                             "robot '" + r.name + "' at " + Where(r.start.x, r.start.y) +
                                 " cannot reach robot '" + first.name + "' (walled off or too near a wall)");
  }
  for (std::uint32_t id : {source, sink}) {
    const auto it = std::find_if(config.markers.begin(), config.markers.end(),
                                 [id](const world_sim::MarkerSpec& m) { return m.id == id; });
    if (it == config.markers.end())
      throw grid::InputError(file, "markers", "expected a marker with id " + std::to_string(id) +
                                                  (id == source ? " (the source)" : " (the sink)"));
    if (room.Region({it->x, it->y}) != region)
      throw grid::InputError(file, "markers[" + std::to_string(it - config.markers.begin()) + "].position",
                             "marker " + std::to_string(id) + " at " + Where(it->x, it->y) +
                                 " cannot be reached by the robots (walled off or too near a wall)");
  }
}

}  // namespace sounds_good_explorer
