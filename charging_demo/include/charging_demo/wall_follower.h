#pragma once

#include <vector>

#include "local_navigation/local_navigator.h"

namespace charging_demo {

struct WallFollowOptions {
  double distance = 0.35;       // m from the robot's centre to the wall it follows
  double speed = 0.25;          // m/s along a wall
  double gain = 3.0;            // rad/s per m the wall is off `distance`
  double turn_rate = 1.5;       // rad/s at most
  double lost_range = 1.0;      // m: no wall this close on the wall side: the wall has ended
  double corner_radius = 0.45;  // m: the arc round the end of a wall (a door jamb, a corner)
};

void ValidateOptions(const WallFollowOptions& options);

enum class Hand { kLeft, kRight };  // the side the wall is kept on

// Follows walls with one hand on them, from the range ring alone: in a room the wall leads round
// to the door and out, along a corridor into every room on that side and out again, which is
// how a robot with no map covers a building. With no wall in reach it drives straight until it
// meets one; where the wall ends it arcs round the end. Readings: the ring of range readings,
// bearings in the robot frame, +inf or NaN for nothing in reach.
class WallFollower {
 public:
  WallFollower(const WallFollowOptions& options, Hand hand);

  local_navigation::Velocity Update(const std::vector<local_navigation::RangeReading>& ranges, double dt);

  // Drops the wall: drive straight on until the next one.
  void Reset();
  bool on_wall() const { return on_wall_; }
  Hand hand() const { return hand_; }

 private:
  WallFollowOptions options_;
  Hand hand_;
  bool on_wall_ = false;
  double arcing_ = 0.0;  // s spent arcing round the end of the wall
};

}  // namespace charging_demo
