#include "charging_demo/charging_behaviour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "grid/option_checks.h"

namespace charging_demo {

using grid::RequireAbove;
using grid::RequireAtLeast;

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
  RequireAbove("charging undock_timeout", o.undock_timeout, 0.0);
  RequireAbove("charging undock_min_distance", o.undock_min_distance, 0.0);
  RequireAbove("charging lock_timeout", o.lock_timeout, 0.0);
  RequireAbove("charging dock_timeout", o.dock_timeout, 0.0);
  RequireAbove("charging same_charger", o.same_charger, 0.0);
  RequireAbove("charging recheck_distance", o.recheck_distance, 0.0);
  RequireAbove("charging recheck_time", o.recheck_time, 0.0);
  RequireAbove("charging approach_timeout", o.approach_timeout, 0.0);
  RequireAtLeast("charging max_redocks", o.max_redocks, 0.0);
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

std::vector<Eigen::Vector2d> ChargingBehaviour::known_chargers() const {
  std::vector<Eigen::Vector2d> out;
  for (const Known& k : known_) out.push_back(k.position);
  return out;
}

std::optional<Eigen::Vector2d> ChargingBehaviour::ChooseCharger(const Eigen::Vector2d& robot,
                                                                double time) const {
  std::optional<Eigen::Vector2d> best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const Known& k : known_) {
    const bool avoided = std::any_of(avoid_.begin(), avoid_.end(), [&](const Avoided& a) {
      return a.until > time && (a.position - k.position).norm() < options_.same_charger;
    });
    if (avoided) continue;
    const double d = (k.position - robot).norm();
    if (d < best_distance) best_distance = d, best = k.position;
  }
  return best;
}

Eigen::Vector2d ChargingBehaviour::WaitingPoint(const Eigen::Vector2d& robot) const {
  // On the side the charger was last seen from: the ring's point on that line of sight is in
  // sight of the charger too (the nearest point to the robot may be behind a door jamb).
  const Eigen::Vector2d from = (charger_seen_from_ - *charger_).norm() > 1e-6 ? charger_seen_from_ : robot;
  const Eigen::Vector2d away = from - *charger_;
  const Eigen::Vector2d direction = away.norm() > 1e-6 ? away.normalized() : Eigen::Vector2d(1, 0);
  return *charger_ + direction * options_.wait_distance;
}

void ChargingBehaviour::See(const std::vector<ChargerSighting>& sightings, const grid::Pose2D& odom,
                            double time) {
  for (const ChargerSighting& s : sightings) {
    if (!options_.chargers.count(s.id)) continue;
    const Eigen::Vector2d p = grid::TransformPoint(
        odom, {s.range * std::cos(s.bearing), s.range * std::sin(s.bearing)});
    auto known = std::find_if(known_.begin(), known_.end(), [&](const Known& k) {
      return (k.position - p).norm() < options_.same_charger;
    });
    if (known == known_.end()) {
      // Odometry drifts: a charger remembered from long ago shows up further off than
      // same_charger. The nearest with its marker unseen for recheck_time within
      // recheck_distance is taken to be it, rather than remembering one charger twice (the
      // copy, planned round as another charger, could wall the real one's waiting ring off).
      double nearest = options_.recheck_distance;
      for (auto k = known_.begin(); k != known_.end(); ++k) {
        const double d = (k->position - p).norm();
        if (k->id == s.id && d < nearest && time - k->seen > options_.recheck_time) nearest = d, known = k;
      }
    }
    if (known == known_.end()) known_.push_back({p, s.id, time, -1.0, odom.position()});
    else known->position = p, known->seen = time, known->seen_from = odom.position();  // odometry drifts
    if (!charger_) continue;
    // The charger in use follows its sightings. One remembered from long ago may be off by
    // more than same_charger; if it has gone unseen for recheck_time while a charger is in
    // sight within recheck_distance of it, that one is taken to be it.
    const double offset = (*charger_ - p).norm();
    if (offset < options_.same_charger ||
        (time - charger_seen_ > options_.recheck_time && offset < options_.recheck_distance)) {
      charger_ = p;
      charger_seen_ = time;
      charger_seen_from_ = odom.position();
    }
  }
}

void ChargingBehaviour::ForgetUnseen(const ChargingInputs& in) {
  const Eigen::Vector2d robot = in.odom.position();
  const double time = in.time;
  // Charging and leaving, the charger is where the robot is; waiting and docking, it must
  // still be in sight (a charger remembered through a wall is no charger to wait at).
  const bool in_use = phase_ == Phase::kCharge || phase_ == Phase::kUndock;
  auto gone = [&](const Known& k) {
    if (in_use && charger_ && (k.position - *charger_).norm() < options_.same_charger) return false;
    return k.near_since >= 0.0 && time - std::max(k.seen, k.near_since) > options_.recheck_time;
  };
  for (Known& k : known_) {
    // Near and in view: a charger remembered behind a wall is not missing.
    const bool near = (k.position - robot).norm() < options_.recheck_distance && (!in.in_view || in.in_view(k.position));
    if (!near) k.near_since = -1.0;
    else if (k.near_since < 0.0) k.near_since = time;
    if (!gone(k)) continue;
    ++forgotten_;
    if (charger_ && (k.position - *charger_).norm() < options_.same_charger) {
      charger_.reset();
      retry_dock_ = false;
      redocks_in_row_ = 0;
      Enter(Phase::kSeek, time);  // from approach, wait or dock: the lock is let go
    }
  }
  known_.erase(std::remove_if(known_.begin(), known_.end(), gone), known_.end());
}

void ChargingBehaviour::GiveUp(double time) {
  ++give_ups_;
  avoid_.push_back({*charger_, time + options_.avoid_time});
  charger_.reset();
  retry_dock_ = false;
  redocks_in_row_ = 0;
  Enter(Phase::kSeek, time);
}

ChargingCommand ChargingBehaviour::Update(const ChargingInputs& in) {
  const Eigen::Vector2d robot = in.odom.position();
  See(in.sightings, in.odom, in.time);
  ForgetUnseen(in);
  avoid_.erase(std::remove_if(avoid_.begin(), avoid_.end(),
                              [&](const Avoided& a) { return a.until <= in.time; }),
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
      for (const Known& k : known_)
        if ((k.position - *charger_).norm() < 1e-9) charger_seen_ = k.seen, charger_seen_from_ = k.seen_from;
      Enter(Phase::kApproach, in.time);
      approach_best_ = std::numeric_limits<double>::infinity();
      approach_improved_ = in.time;
      [[fallthrough]];
    case Phase::kApproach: {
      const double distance = (robot - *charger_).norm();
      if (in.making_way) {
        approach_best_ = distance;  // progress is measured afresh from where that way leads
        approach_improved_ = in.time;
      } else if (distance < approach_best_ - kApproachProgress) {
        approach_best_ = distance;
        approach_improved_ = in.time;
      } else if (in.time - approach_improved_ > options_.approach_timeout) {
        GiveUp(in.time);
        return cmd;
      }
      // Anywhere on the ring wait_distance from the charger will do: the target is the ring's
      // point towards where the robot saw it from, so robots arriving from different sides wait
      // on different sides. But
      // only in sight of it: on the ring behind a wall the robot is not there yet (and the
      // navigation must find another way, or the approach times out).
      if (std::abs(distance - options_.wait_distance) > options_.arrive_tolerance ||
          in.time - charger_seen_ > options_.recheck_time) {
        cmd.motion = ChargingCommand::Motion::kGoTo;
        cmd.target = WaitingPoint(robot);
        return cmd;
      }
      Enter(Phase::kWait, in.time);
    }
      [[fallthrough]];
    case Phase::kWait:
      if (in.lock != local_mutex::State::kHeld) {
        if (in.time - phase_since_ > options_.lock_timeout) {
          // The documented fallback: withdraw, avoid this charger for a while, look for another.
          GiveUp(in.time);
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
        redocks_in_row_ = 0;
        Enter(Phase::kCharge, in.time);
      } else if (in.time - phase_since_ > options_.dock_timeout) {
        ++redocks_;
        retry_dock_ = ++redocks_in_row_ <= options_.max_redocks;
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
    case Phase::kUndock: {
      const double distance = (robot - *charger_).norm();
      // Off the charger by distance, or by its contacts (odometry may be off, or something
      // behind stops the reversing): enough once undock_timeout has passed.
      const bool hemmed_in = in.time - phase_since_ > options_.undock_timeout &&
                             (distance >= options_.undock_min_distance || !in.docked);
      if (distance < options_.undock_distance && !hemmed_in) {
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
      if (redocks_in_row_ > options_.max_redocks) {
        GiveUp(in.time);  // backed out of the last failed docking: let go, try elsewhere
        return cmd;
      }
      charger_.reset();
      Enter(Phase::kDuty, in.time);
      return cmd;  // released: want_lock false
    }
  }
  return cmd;
}

}  // namespace charging_demo
