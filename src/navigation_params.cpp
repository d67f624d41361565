#include "navigation_params.h"

#include "params.h"

namespace multirobot_audio {

void ReadNavigationParams(const ros::NodeHandle& pnh, local_navigation::LocalMapOptions& map,
                          bool& clear_sectors, local_navigation::PlannerOptions& planner,
                          local_navigation::MotionOptions& motion) {
  constexpr double kBig = 1e6;
  map.size = IntParam(pnh, "local_map_size", map.size, 1, 10001);
  map.resolution = PositiveParam(pnh, "resolution", map.resolution, 100.0);
  map.expiry = PositiveParam(pnh, "expiry", map.expiry);
  map.expiry_step = PositiveParam(pnh, "expiry_step", map.expiry_step);
  clear_sectors = BoolParam(pnh, "clear_sectors", clear_sectors);
  planner.robot_radius = PositiveParam(pnh, "robot_radius", planner.robot_radius, 100.0);
  planner.risk_scale = NumberParam(pnh, "risk_scale", planner.risk_scale, 0.0, kBig);
  planner.risk_decay = PositiveParam(pnh, "risk_decay", planner.risk_decay);
  planner.grown_cost = NumberParam(pnh, "grown_cost", planner.grown_cost, 0.0, kBig);
  motion.max_speed = PositiveParam(pnh, "max_speed", motion.max_speed, 100.0);
  motion.max_turn_rate = PositiveParam(pnh, "max_turn_rate", motion.max_turn_rate, 100.0);
  motion.turn_gain = PositiveParam(pnh, "turn_gain", motion.turn_gain, 1000.0);
  motion.lookahead = PositiveParam(pnh, "lookahead", motion.lookahead, 100.0);
  motion.goal_tolerance = PositiveParam(pnh, "goal_tolerance", motion.goal_tolerance, 100.0);
  motion.goal_hold = NumberParam(pnh, "goal_hold", motion.goal_hold, 0.0, kBig);
  motion.replan_period = PositiveParam(pnh, "replan_period", motion.replan_period);
  motion.stuck_time = PositiveParam(pnh, "stuck_time", motion.stuck_time);
  motion.backoff_time = PositiveParam(pnh, "backoff_time", motion.backoff_time);
}

}  // namespace multirobot_audio
