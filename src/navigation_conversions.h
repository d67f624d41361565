#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/time.h>
#include <sensor_msgs/LaserScan.h>

#include "local_navigation/local_map.h"
#include "local_navigation/local_navigator.h"

// Pure conversions between ROS messages and what local_navigation uses, and of its state (local
// map, plan) for rviz; shared by every node that drives with it (the Sounds Good explorer, the
// charging robots).
namespace multirobot_audio {

// A ring of rangers as range readings: reading k's bearing is angle_min + k * angle_increment
// (robot frame), its range is as given (measured from the robot's centre, as world_sim's IR
// ring is; +inf or NaN for nothing in reach). The rangers' reach is the scan's range_max.
std::vector<local_navigation::RangeReading> ToRangeReadings(const sensor_msgs::LaserScan& scan);

// The local map in its odom frame: occupied -> 100, free -> 0, unknown -> -1; cell (0, 0)'s
// lower-left corner at origin() * resolution.
nav_msgs::OccupancyGrid ToOccupancyGrid(const local_navigation::LocalMap& map,
                                        const std::string& frame, const ros::Time& stamp);

// Points as a path; each pose faces the next point (the last keeps the heading of the step
// into it).
nav_msgs::Path ToPath(const std::vector<Eigen::Vector2d>& points, const std::string& frame,
                      const ros::Time& stamp);

}  // namespace multirobot_audio
