#include "sounds_good_conversions.h"

#include <cmath>

#include "conversions.h"

namespace multirobot_audio {

nav_msgs::OccupancyGrid ToOccupancyGrid(const sounds_good_explorer::LocalMap& map, const std::string& frame,
                                        const ros::Time& stamp) {
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.info.map_load_time = stamp;
  msg.info.resolution = static_cast<float>(map.resolution());
  msg.info.width = static_cast<std::uint32_t>(map.size());
  msg.info.height = static_cast<std::uint32_t>(map.size());
  // Cell (0, 0) spans [origin, origin + 1) odom cells: its lower-left corner is the grid's origin.
  msg.info.origin.position.x = map.origin().x() * map.resolution();
  msg.info.origin.position.y = map.origin().y() * map.resolution();
  msg.info.origin.orientation.w = 1.0;
  msg.data.reserve(map.cells().size());
  for (sounds_good_explorer::CellState c : map.cells()) {
    msg.data.push_back(c == sounds_good_explorer::CellState::kOccupied ? 100 : c == sounds_good_explorer::CellState::kFree ? 0 : -1);
  }
  return msg;
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
