#include "navigation_conversions.h"

#include <cmath>

#include "conversions.h"

namespace multirobot_audio {

std::vector<local_navigation::RangeReading> ToRangeReadings(const sensor_msgs::LaserScan& scan) {
  std::vector<local_navigation::RangeReading> readings(scan.ranges.size());
  for (std::size_t k = 0; k < readings.size(); ++k) {
    readings[k].bearing = scan.angle_min + static_cast<double>(k) * static_cast<double>(scan.angle_increment);
    readings[k].range = scan.ranges[k];
  }
  return readings;
}

nav_msgs::OccupancyGrid ToOccupancyGrid(const local_navigation::LocalMap& map,
                                        const std::string& frame, const ros::Time& stamp) {
  // Cell (0, 0) spans [origin, origin + 1) odom cells: its lower-left corner is the grid's
  // origin. Going through grid::OccupancyMap keeps one message layout for every map we publish.
  const double res = map.resolution();
  grid::OccupancyMap grid(map.size(), map.size(), res,
                          {map.origin().x() * res, map.origin().y() * res, 0.0});
  for (int y = 0; y < map.size(); ++y) {
    for (int x = 0; x < map.size(); ++x) {
      const local_navigation::CellState c = map.at({x, y});
      grid.set(x, y, c == local_navigation::CellState::kOccupied ? grid::Cell::kOccupied
                     : c == local_navigation::CellState::kFree   ? grid::Cell::kFree
                                                                      : grid::Cell::kUnknown);
    }
  }
  return ToOccupancyGrid(grid, frame, stamp);
}

nav_msgs::Path ToPath(const std::vector<Eigen::Vector2d>& points, const std::string& frame,
                      const ros::Time& stamp) {
  nav_msgs::Path msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  double yaw = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    // The last pose keeps the heading of the step into it.
    if (i + 1 < points.size()) {
      const Eigen::Vector2d step = points[i + 1] - points[i];
      yaw = std::atan2(step.y(), step.x());
    }
    geometry_msgs::PoseStamped pose;
    pose.header = msg.header;
    pose.pose.position.x = points[i].x();
    pose.pose.position.y = points[i].y();
    pose.pose.orientation = ToYawQuaternion(yaw);
    msg.poses.push_back(pose);
  }
  return msg;
}

}  // namespace multirobot_audio
