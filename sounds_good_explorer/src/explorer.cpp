#include "sounds_good_explorer/explorer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sounds_good_explorer/frontiers.h"
#include "sounds_good_explorer/marker_packet.h"

namespace sounds_good_explorer {

namespace {

// How long a goal found unreachable stays excluded from the frontier choice.
constexpr double kUnreachableMemory = 30.0;

}  // namespace

void ValidateOptions(const ExplorerOptions& o) {
  local_navigation::ValidateOptions(
      local_navigation::NavigatorOptions{o.map, o.clear_sectors, o.planner, o.motion});
  ValidateOptions(o.frontier);
  ValidateOptions(o.audio);
  ValidateOptions(o.task);
  if (o.task.source > kMaxMarkerId || o.task.sink > kMaxMarkerId)
    throw std::invalid_argument("task marker ids must be at most " + std::to_string(kMaxMarkerId) +
                                " to be announced");
}

Explorer::Explorer(const ExplorerOptions& options)
    : options_((ValidateOptions(options), options)),
      nav_(local_navigation::NavigatorOptions{options.map, options.clear_sectors, options.planner,
                                              options.motion}),
      heard_(options.audio),
      task_(options.task),
      rng_(options.seed) {}

void Explorer::OnSightings(const std::vector<MarkerSighting>& sightings, double time) {
  if (!nav_.have_pose()) return;
  for (const MarkerSighting& s : sightings)
    task_.Seen(s.id, grid::TransformPoint(nav_.pose(), {s.range * std::cos(s.bearing),
                                                  s.range * std::sin(s.bearing)}),
               time);
}

void Explorer::OnHeard(const std::vector<std::uint8_t>& data, double level_db, double direction,
                       double time) {
  const std::optional<std::uint32_t> marker = DecodeMarkerPacket(data);
  if (!marker) {
    ++foreign_packets_;
    return;
  }
  heard_.Add(*marker, direction, nav_.pose().yaw, level_db, time, options_.mode);
}

ExplorerOutput Explorer::Update(double time) {
  ExplorerOutput out;
  nav_.Expire(time);
  heard_.Forget(time);
  const Eigen::Vector2d here = nav_.pose().position();
  out.job = task_.Update(here, time);
  if (out.job) {
    goal_.reset();
    unreachable_.clear();
  }
  for (std::uint32_t marker : task_.DueAnnouncements(time)) {
    // An id the 16-bit announcement cannot carry (another robot's charger, say) goes unsaid.
    if (marker <= kMaxMarkerId) out.packets.push_back(EncodeMarkerPacket(marker));
    else ++unannounced_;
  }
  if (!nav_.have_pose() || task_.working()) {
    nav_.Hold(time);
    return out;
  }
  if (nav_.BackingOff(time)) {
    const local_navigation::Velocity back = nav_.BackoffCommand();
    out.v = back.v;
    out.w = back.w;
    return out;
  }

  const std::optional<Eigen::Vector2d> marker = task_.SoughtPosition(time);
  bool new_goal = false;
  if (marker) {
    new_goal = !goal_is_marker_ || !goal_;
    goal_ = marker;
    goal_is_marker_ = true;
  } else if (!goal_ || goal_is_marker_ || (*goal_ - here).norm() <= options_.motion.goal_tolerance ||
             time - goal_chosen_ >= options_.motion.goal_hold) {
    ChooseGoal(time);
    new_goal = true;
  }
  if (new_goal || nav_.ReplanDue(time)) Replan(time);
  return Steer(time, out);
}

void Explorer::ChooseGoal(double time) {
  const local_navigation::LocalMap& map = nav_.map();
  goal_is_marker_ = false;
  goal_chosen_ = time;
  unreachable_.erase(std::remove_if(unreachable_.begin(), unreachable_.end(),
                                    [&](const auto& u) { return time - u.second > kUnreachableMemory; }),
                     unreachable_.end());
  std::vector<Eigen::Vector2i> excluded;
  for (const auto& u : unreachable_) excluded.push_back(u.first - map.origin());
  goal_.reset();
  const std::optional<Eigen::Vector2i> cell =
      ChooseFrontier(map, FindFrontiers(map), nav_.pose().position(), heard_, task_.sought(), time,
                     options_.frontier, rng_, excluded);
  if (cell) goal_ = map.CentreOf(*cell);
}

void Explorer::Replan(double time) {
  if (nav_.PlanTo(goal_, time) || !goal_) return;
  // Walled off in the local map: remember not to choose it again for a while.
  if (!goal_is_marker_) unreachable_.emplace_back(nav_.GoalCell(*goal_) + nav_.map().origin(), time);
  goal_.reset();
}

ExplorerOutput Explorer::Steer(double time, ExplorerOutput out) {
  const local_navigation::LocalNavigator::Steering steering = nav_.Steer(time);
  out.v = steering.command.v;
  out.w = steering.command.w;
  if (steering.stuck) {
    const local_navigation::LocalMap& map = nav_.map();
    if (goal_ && !goal_is_marker_) unreachable_.emplace_back(map.CellOf(*goal_) + map.origin(), time);
    goal_.reset();
    const double max_turn = options_.motion.max_turn_rate;
    nav_.StartBackoff(time, (std::bernoulli_distribution(0.5)(rng_) ? 0.5 : -0.5) * max_turn);
  }
  return out;
}

}  // namespace sounds_good_explorer
