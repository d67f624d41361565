#pragma once

#include <ros/ros.h>

namespace multirobot_audio::testing {

// Spins callbacks until `done()` holds or `wall_seconds` of wall time pass; returns done().
template <typename Pred>
bool WaitFor(Pred done, double wall_seconds) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(wall_seconds);
  while (ros::ok() && ros::WallTime::now() < end) {
    ros::spinOnce();
    if (done()) return true;
    ros::WallDuration(0.005).sleep();
  }
  return done();
}

}  // namespace multirobot_audio::testing
