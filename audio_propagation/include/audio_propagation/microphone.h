#pragma once

#include <random>

#include "audio_propagation/direction_errors.h"
#include "world_sim/world_config.h"

namespace audio_propagation {

// What a robot's microphone reports of where a sound came from, in the robot's frame (rad, CCW
// from ahead), given the world-frame direction of arrival and the robot's heading:
//  - omni: the true direction, plus Gaussian noise of `noise_std` rad (none when 0);
//  - bidirectional: one bit, front (0) or back (pi) half-plane;
//  - none: NaN (the robot hears the packet but not where it came from).
// A NaN arrival (the listener stands on the source) gives NaN.
double SenseDirection(world_sim::Microphone microphone, double arrival_world, double robot_yaw,
                      double noise_std, std::mt19937& rng);

// The same, as a real array reports it over a link of `drr_db` in a room of `rt60` s: drawn
// from `errors` (DirectionErrors::Sense), with the array's confidence.
SensedDirection SenseDirection(world_sim::Microphone microphone, double arrival_world, double robot_yaw,
                               const DirectionErrors& errors, double drr_db, double rt60, std::mt19937& rng);

}  // namespace audio_propagation
