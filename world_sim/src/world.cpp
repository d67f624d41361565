#include "world_sim/world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "world_sim/battery.h"
#include "world_sim/collision.h"
#include "world_sim/ir_rangers.h"
#include "world_sim/kinematics.h"
#include "world_sim/world_file.h"

namespace world_sim {
namespace {

void CheckPeriod(double period, double step, const char* name) {
  if (!(period >= step) || !std::isfinite(period)) {
    throw std::invalid_argument(std::string("world_sim: ") + name + " must be >= step (" +
                                std::to_string(step) + " s), got " + std::to_string(period));
  }
}

}  // namespace

void ValidateOptions(const WorldOptions& o) {
  if (!(o.step > 0.0) || !(o.step <= 1.0)) {
    throw std::invalid_argument("world_sim: step must be in (0, 1] s, got " + std::to_string(o.step));
  }
  if (!(o.start_time > 0.0)) {
    throw std::invalid_argument("world_sim: start_time must be positive, got " + std::to_string(o.start_time));
  }
  CheckPeriod(o.scan_period, o.step, "scan_period");
  CheckPeriod(o.camera_period, o.step, "camera_period");
  CheckPeriod(o.odom_period, o.step, "odom_period");
}

std::uint64_t StepsPerPeriod(double period, double step) {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(period / step)));
}

World::World(grid::OccupancyMap map, WorldConfig config, const WorldOptions& options)
    : map_(std::move(map)), config_(std::move(config)), options_(options) {
  ValidateOptions(options_);
  scan_every_ = StepsPerPeriod(options_.scan_period, options_.step);
  camera_every_ = StepsPerPeriod(options_.camera_period, options_.step);
  odom_every_ = StepsPerPeriod(options_.odom_period, options_.step);
  ValidateWorld(config_.map_file, config_, map_);

  for (std::size_t k = 0; k < config_.robots.size(); ++k) {
    const RobotSpec& spec = config_.robots[k];
    RobotState r;
    r.name = spec.name;
    r.pose = spec.start;
    r.battery = spec.battery;
    robots_.push_back(r);
    odom_anchor_.push_back(r.pose);
    // Each robot draws its own noise so that adding a robot does not change the others'.
    drift_.emplace_back(config_.model.odometry, config_.seed * 7919u + static_cast<std::uint32_t>(k));
  }
  fiducials_ = config_.markers;
  for (const ChargerSpec& c : config_.chargers) {
    if (c.marker) fiducials_.push_back({*c.marker, c.pose.x, c.pose.y});
  }
  for (std::size_t k = 0; k < robots_.size(); ++k) robots_[k].docked = Docked(robots_[k].pose.position());
  TakeReadings();
}

void World::SetCommand(std::size_t index, double v, double w) {
  RobotState& r = robots_.at(index);
  const RobotModel& m = config_.model;
  r.cmd_v = std::isfinite(v) ? std::clamp(v, -m.max_speed, m.max_speed) : 0.0;
  r.cmd_w = std::isfinite(w) ? std::clamp(w, -m.max_turn_rate, m.max_turn_rate) : 0.0;
}

std::optional<std::size_t> World::RobotIndex(const std::string& name) const {
  for (std::size_t k = 0; k < robots_.size(); ++k) {
    if (robots_[k].name == name) return k;
  }
  return std::nullopt;
}

bool World::Collides(std::size_t index, const Eigen::Vector2d& centre) const {
  if (DiscHitsWalls(map_, centre, config_.model.radius)) return true;
  const double min_gap = 2.0 * config_.model.radius;
  for (std::size_t k = 0; k < robots_.size(); ++k) {
    if (k != index && (robots_[k].pose.position() - centre).squaredNorm() < min_gap * min_gap) {
      return true;
    }
  }
  return false;
}

bool World::Docked(const Eigen::Vector2d& centre) const {
  for (const ChargerSpec& c : config_.chargers) {
    if ((c.pose.position() - centre).norm() <= c.radius) return true;
  }
  return false;
}

void World::MoveRobot(std::size_t index) {
  RobotState& r = robots_[index];
  const double dt = options_.step;
  const bool powered = r.battery > 0.0;
  const double v = powered ? r.cmd_v : 0.0, w = powered ? r.cmd_w : 0.0;
  const grid::Pose2D before = r.pose;
  grid::Pose2D after = IntegrateUnicycle(before, v, w, dt);
  bool stalled = false;
  if (v != 0.0 && Collides(index, after.position())) {
    // A disc turning in place cannot hit anything: keep the turn, drop the translation.
    stalled = true;
    after = {before.x, before.y, grid::NormalizeAngle(before.yaw + w * dt)};
  }
  if (stalled && !r.stalled) ++r.collisions;
  r.stalled = stalled;
  const double moved = (after.position() - before.position()).norm();
  r.pose = after;
  r.v = stalled ? 0.0 : v;
  r.w = w;
  r.distance += moved;
  r.docked = Docked(after.position());
  r.battery = StepBattery(r.battery, config_.model.battery, dt, moved, r.docked);
}

void World::TakeReadings() {
  if (steps_ % odom_every_ == 0) {
    // Drift is applied to the motion of a whole odometry period, as encoders are read.
    for (std::size_t k = 0; k < robots_.size(); ++k) {
      robots_[k].odom = drift_[k].Update(odom_anchor_[k], robots_[k].pose);
      robots_[k].odom_step = steps_;
      odom_anchor_[k] = robots_[k].pose;
    }
  }
  const bool scan = steps_ % scan_every_ == 0, camera = steps_ % camera_every_ == 0;
  if (!scan && !camera) return;
  std::vector<Eigen::Vector2d> others;
  for (std::size_t k = 0; k < robots_.size(); ++k) {
    RobotState& r = robots_[k];
    if (scan) {
      others.clear();
      for (std::size_t q = 0; q < robots_.size(); ++q) {
        if (q != k) others.push_back(robots_[q].pose.position());
      }
      r.scan = IrRanges(map_, config_.model, r.pose, others);
      r.scan_step = steps_;
    }
    if (camera) {
      r.fiducials = SeeFiducials(map_, config_.model, r.pose, fiducials_);
      r.fiducials_step = steps_;
    }
  }
}

void World::Step() {
  for (std::size_t k = 0; k < robots_.size(); ++k) MoveRobot(k);
  ++steps_;
  TakeReadings();
}

int World::TotalCollisions() const {
  int n = 0;
  for (const RobotState& r : robots_) n += r.collisions;
  return n;
}

double World::TotalDistance() const {
  double d = 0.0;
  for (const RobotState& r : robots_) d += r.distance;
  return d;
}

}  // namespace world_sim
