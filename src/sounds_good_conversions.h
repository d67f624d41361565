#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/time.h>

#include "sounds_good_explorer/local_map.h"

// Pure conversions of the Sounds Good explorer's state to ROS messages, for rviz.
namespace multirobot_audio {

// The local map in its odom frame: occupied -> 100, free -> 0, unknown -> -1; cell (0, 0)'s
// lower-left corner at origin() * resolution.
nav_msgs::OccupancyGrid ToOccupancyGrid(const sounds_good_explorer::LocalMap& map,
                                        const std::string& frame, const ros::Time& stamp);

// Points as a path; each pose faces the next point (the last keeps the heading of the step
// into it).
nav_msgs::Path ToPath(const std::vector<Eigen::Vector2d>& points, const std::string& frame,
                      const ros::Time& stamp);

}  // namespace multirobot_audio
