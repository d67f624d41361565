#pragma once

#include <ros/node_handle.h>

#include "local_navigation/local_navigator.h"

namespace multirobot_audio {

// The local-map navigation's ~params, with the same names in every node that drives with it
// (sounds_good_explorer, charging_demo): local_map_size, resolution, expiry, expiry_step,
// clear_sectors, robot_radius, risk_scale, risk_decay, grown_cost, max_speed, max_turn_rate,
// turn_gain, lookahead, goal_tolerance, goal_hold, replan_period, stuck_time, backoff_time.
// Unset ones keep the values given; a bad one throws ParamError naming it.
void ReadNavigationParams(const ros::NodeHandle& pnh, local_navigation::LocalMapOptions& map,
                          bool& clear_sectors, local_navigation::PlannerOptions& planner,
                          local_navigation::MotionOptions& motion);

}  // namespace multirobot_audio
