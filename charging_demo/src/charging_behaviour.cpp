#include "charging_demo/charging_behaviour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sounds_good_explorer/option_checks.h"

namespace charging_demo {

using sounds_good_explorer::RequireAbove;
using sounds_good_explorer::RequireAtLeast;

void ValidateOptions(const ChargingOptions& o) {
  if (o.chargers.empty())
    throw std::invalid_argument("charging chargers: expected at least one charger fiducial id");
  if (!(o.low_battery > 0.0 && o.low_battery < 1.0))
    throw std::invalid_argument("charging low_battery must be within (0, 1), got " +
                                std::to_string(o.low_battery));
  if (!(o.full_battery > o.low_battery && o.full_battery <= 1.0))
    throw std::invalid_argument("charging full_battery must be within (low_battery, 1], got " +
                                std::to_string(o.full_battery));
  RequireAbove("charging wait_distance", o.wait_distance, 0.0);
  RequireAbove("charging arrive_tolerance", o.arrive_tolerance, 0.0);
  RequireAbove("charging undock_distance", o.undock_distance, 0.0);
  RequireAbove("charging lock_timeout", o.lock_timeout, 0.0);
  RequireAbove("charging dock_timeout", o.dock_timeout, 0.0);
  RequireAbove("charging same_charger", o.same_charger, 0.0);
  RequireAtLeast("charging avoid_time (s)", o.avoid_time, 0.0);
}

const char* PhaseName(Phase phase) {
  switch (phase) {
    case Phase::kDuty: return "duty";
    case Phase::kSeek: return "seek";
    case Phase::kApproach: return "approach";
    case Phase::kWait: return "wait";
    case Phase::kDock: return "dock";
    case Phase::kCharge: return "charge";
    case Phase::kUndock: return "undock";
  }
  return "?";
}

ChargingBehaviour::ChargingBehaviour(const ChargingOptions& options) : options_(options) {
  ValidateOptions(options_);
}

void ChargingBehaviour::Enter(Phase phase, double time) {
  phase_ = phase;
  phase_since_ = time;
}

std::optional<Eigen::Vector2d> ChargingBehaviour::ChooseCharger(const Eigen::Vector2d& robot,
                                                                double time) const {
  std::optional<Eigen::Vector2d> best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& c : known_) {
    const bool avoided = std::any_of(avoid_.begin(), avoid_.end(), [&](const auto& a) {
      return a.second > time && (a.first - c).norm() < options_.same_charger;
    });
    if (avoided) continue;
    const double d = (c - robot).norm();
    if (d < best_distance) best_distance = d, best = c;
  }
  return best;
}

Eigen::Vector2d ChargingBehaviour::WaitingPoint(const Eigen::Vector2d& robot) const {
  const Eigen::Vector2d away = robot - *charger_;
  const Eigen::Vector2d direction = away.norm() > 1e-6 ? away.normalized() : Eigen::Vector2d(1, 0);
  return *charger_ + direction * options_.wait_distance;
}

ChargingCommand ChargingBehaviour::Update(const ChargingInputs& in) {
  const Eigen::Vector2d robot = in.odom.position();
  for (const ChargerSighting& s : in.sightings) {
    if (!options_.chargers.count(s.id)) continue;
    const Eigen::Vector2d p = grid::TransformPoint(
        in.odom, {s.range * std::cos(s.bearing), s.range * std::sin(s.bearing)});
    auto known = std::find_if(known_.begin(), known_.end(), [&](const Eigen::Vector2d& c) {
      return (c - p).norm() < options_.same_charger;
    });
    if (known == known_.end()) known_.push_back(p);
    else *known = p;  // the latest sighting: odometry drifts
  }
  avoid_.erase(std::remove_if(avoid_.begin(), avoid_.end(),
                              [&](const auto& a) { return a.second <= in.time; }),
               avoid_.end());

  ChargingCommand cmd;
  switch (phase_) {
    case Phase::kDuty:
      if (in.battery >= options_.low_battery) return cmd;
      Enter(Phase::kSeek, in.time);
      [[fallthrough]];
    case Phase::kSeek:
      charger_ = ChooseCharger(robot, in.time);
      if (!charger_) return cmd;  // keep exploring until a charger comes into view
      waiting_point_ = WaitingPoint(robot);
      Enter(Phase::kApproach, in.time);
      [[fallthrough]];
    case Phase::kApproach:
      if ((robot - waiting_point_).norm() > options_.arrive_tolerance) {
        cmd.motion = ChargingCommand::Motion::kGoTo;
        cmd.target = waiting_point_;
        return cmd;
      }
      Enter(Phase::kWait, in.time);
      [[fallthrough]];
    case Phase::kWait:
      if (in.lock != local_mutex::State::kHeld) {
        if (in.time - phase_since_ > options_.lock_timeout) {
          // The documented fallback: withdraw, avoid this charger for a while, look for another.
          ++give_ups_;
          avoid_.emplace_back(*charger_, in.time + options_.avoid_time);
          charger_.reset();
          Enter(Phase::kSeek, in.time);
          return cmd;  // want_lock false withdraws the request
        }
        cmd.motion = ChargingCommand::Motion::kStop;
        cmd.want_lock = true;
        return cmd;
      }
      Enter(Phase::kDock, in.time);
      [[fallthrough]];
    case Phase::kDock:
      cmd.want_lock = true;
      if (in.lock != local_mutex::State::kHeld) {
        // Not held (yet, or any more): stand still and keep asking; never dock without it.
        Enter(Phase::kWait, in.time);
        cmd.motion = ChargingCommand::Motion::kStop;
        return cmd;
      }
      if (in.docked) {
        ++charges_;
        Enter(Phase::kCharge, in.time);
      } else if (in.time - phase_since_ > options_.dock_timeout) {
        ++redocks_;
        retry_dock_ = true;
        Enter(Phase::kUndock, in.time);
      } else {
        cmd.motion = ChargingCommand::Motion::kGoTo;
        cmd.target = *charger_;
        return cmd;
      }
      [[fallthrough]];
    case Phase::kCharge:
      if (phase_ == Phase::kCharge) {
        cmd.want_lock = true;
        if (in.battery < options_.full_battery) {
          cmd.motion = in.docked ? ChargingCommand::Motion::kStop : ChargingCommand::Motion::kGoTo;
          cmd.target = *charger_;
          return cmd;
        }
        retry_dock_ = false;
        Enter(Phase::kUndock, in.time);
      }
      [[fallthrough]];
    case Phase::kUndock:
      if ((robot - *charger_).norm() < options_.undock_distance) {
        cmd.motion = ChargingCommand::Motion::kBackAway;
        cmd.target = *charger_;
        cmd.want_lock = true;
        return cmd;
      }
      if (retry_dock_) {
        retry_dock_ = false;
        Enter(Phase::kDock, in.time);
        cmd.motion = ChargingCommand::Motion::kGoTo;
        cmd.target = *charger_;
        cmd.want_lock = true;
        return cmd;
      }
      charger_.reset();
      Enter(Phase::kDuty, in.time);
      return cmd;  // released: want_lock false
  }
  return cmd;
}

}  // namespace charging_demo
