#include "rviz_markers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace multirobot_audio {

namespace {

visualization_msgs::Marker BaseMarker(const std::string& frame, const ros::Time& stamp,
                                      const std::string& ns, int id, int type) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.color.a = 1.0f;
  return m;
}

void SetColour(visualization_msgs::Marker& m, float r, float g, float b, float a = 1.0f) {
  m.color.r = r;
  m.color.g = g;
  m.color.b = b;
  m.color.a = a;
}

}  // namespace

visualization_msgs::MarkerArray ToWorldMarkers(const world_sim::World& world,
                                               const std::string& frame, const ros::Time& stamp) {
  using visualization_msgs::Marker;
  visualization_msgs::MarkerArray out;
  const double r = world.config().model.radius;
  int id = 0;
  for (const world_sim::RobotState& robot : world.robots()) {
    Marker body = BaseMarker(frame, stamp, "robots", id, Marker::CYLINDER);
    body.pose.position.x = robot.pose.x;
    body.pose.position.y = robot.pose.y;
    body.pose.position.z = 0.05;
    body.scale.x = body.scale.y = 2.0 * r;
    body.scale.z = 0.1;
    if (robot.stalled) {
      SetColour(body, 0.9f, 0.1f, 0.1f);
    } else {
      SetColour(body, 0.1f, 0.4f, 0.9f);
    }
    out.markers.push_back(body);

    Marker heading = BaseMarker(frame, stamp, "headings", id, Marker::ARROW);
    heading.pose.position.x = robot.pose.x;
    heading.pose.position.y = robot.pose.y;
    heading.pose.position.z = 0.11;
    heading.pose.orientation = ToYawQuaternion(robot.pose.yaw);
    heading.scale.x = 2.0 * r;
    heading.scale.y = heading.scale.z = 0.04;
    SetColour(heading, 1.0f, 1.0f, 1.0f);
    out.markers.push_back(heading);

    Marker name = BaseMarker(frame, stamp, "names", id, Marker::TEXT_VIEW_FACING);
    name.pose.position.x = robot.pose.x;
    name.pose.position.y = robot.pose.y + 2.0 * r;
    name.pose.position.z = 0.3;
    name.scale.z = 0.4;
    name.text = robot.name;
    SetColour(name, 0.0f, 0.0f, 0.0f);
    out.markers.push_back(name);
    ++id;
  }
  id = 0;
  for (const world_sim::MarkerSpec& m : world.config().markers) {
    Marker cube = BaseMarker(frame, stamp, "fiducials", id++, Marker::CUBE);
    cube.pose.position.x = m.x;
    cube.pose.position.y = m.y;
    cube.pose.position.z = 0.1;
    cube.scale.x = cube.scale.y = cube.scale.z = 0.2;
    SetColour(cube, 1.0f, 0.6f, 0.0f);
    out.markers.push_back(cube);
    Marker label = BaseMarker(frame, stamp, "fiducial_ids", id, Marker::TEXT_VIEW_FACING);
    label.pose = cube.pose;
    label.pose.position.z = 0.4;
    label.scale.z = 0.25;
    label.text = std::to_string(m.id);
    SetColour(label, 0.0f, 0.0f, 0.0f);
    out.markers.push_back(label);
  }
  id = 0;
  for (const world_sim::ChargerSpec& c : world.config().chargers) {
    Marker zone = BaseMarker(frame, stamp, "chargers", id++, Marker::CYLINDER);
    zone.pose.position.x = c.pose.x;
    zone.pose.position.y = c.pose.y;
    zone.pose.position.z = 0.005;
    zone.scale.x = zone.scale.y = 2.0 * c.radius;
    zone.scale.z = 0.01;
    SetColour(zone, 0.1f, 0.8f, 0.2f, 0.6f);
    out.markers.push_back(zone);
  }
  return out;
}

visualization_msgs::Marker ToDirectionMarker(double direction, double confidence, bool packet, const std::string& frame,
                                             const ros::Time& stamp, int id) {
  visualization_msgs::Marker m = BaseMarker(frame, stamp, "direction", id, visualization_msgs::Marker::ARROW);
  const double length = 0.3 + 0.7 * std::clamp(confidence, 0.0, 1.0);
  geometry_msgs::Point tail, head;
  head.x = length * std::cos(direction);
  head.y = length * std::sin(direction);
  m.points = {tail, head};
  m.scale.x = 0.04;  // shaft diameter
  m.scale.y = 0.08;  // head diameter
  m.scale.z = 0.1;   // head length
  if (packet) {
    SetColour(m, 0.1f, 0.8f, 0.1f);
  } else {
    SetColour(m, 1.0f, 0.5f, 0.1f);
  }
  m.lifetime = ros::Duration(3.0);
  return m;
}

namespace {

geometry_msgs::Point ToPoint(const Eigen::Vector2d& p, double z) {
  geometry_msgs::Point out;
  out.x = p.x();
  out.y = p.y();
  out.z = z;
  return out;
}

}  // namespace

visualization_msgs::MarkerArray ToSoundPathMarkers(const std::vector<audio_propagation::Transmission>& started,
                                                   const std::vector<std::string>& robots,
                                                   const audio_propagation::PropagationOptions& levels,
                                                   double display_time, const std::string& frame,
                                                   const ros::Time& stamp, int first_id) {
  visualization_msgs::MarkerArray out;
  for (const audio_propagation::Transmission& tx : started) {
    const bool acoustic = !tx.probability.empty();
    for (std::size_t r = 0; r < tx.paths.size(); ++r) {
      const audio_propagation::SoundPath& p = tx.paths[r];
      if (acoustic ? tx.probability[r] < 0.01 : !p.audible) continue;
      visualization_msgs::Marker m = BaseMarker(frame, stamp, robots.at(tx.sender),
                                                first_id + static_cast<int>(out.markers.size()),
                                                visualization_msgs::Marker::LINE_STRIP);
      m.scale.x = 0.04;
      m.lifetime = ros::Duration(std::max(tx.duration, display_time));
      if (acoustic) {
        const float sure = static_cast<float>(tx.probability[r]);
        SetColour(m, 1.0f - sure, sure, 0.1f, 0.9f);
      } else {
        const double span = levels.source_level_db - levels.threshold_db;
        const float loud = static_cast<float>(std::clamp((p.level_db - levels.threshold_db) / span, 0.0, 1.0));
        SetColour(m, loud, 0.2f, 1.0f - loud, 0.9f);
      }
      for (const Eigen::Vector2d& q : p.polyline) m.points.push_back(ToPoint(q, 0.15));
      out.markers.push_back(m);
    }
  }
  return out;
}

visualization_msgs::MarkerArray ToDiffractionPointMarkers(const std::vector<Eigen::Vector2d>& corners,
                                                          const std::string& frame) {
  visualization_msgs::Marker m = BaseMarker(frame, ros::Time(), "corners", 0, visualization_msgs::Marker::POINTS);
  m.scale.x = m.scale.y = 0.08;
  SetColour(m, 0.2f, 0.8f, 0.0f);
  for (const Eigen::Vector2d& c : corners) m.points.push_back(ToPoint(c, 0.05));
  visualization_msgs::MarkerArray out;
  out.markers.push_back(m);
  return out;
}

visualization_msgs::MarkerArray ToRoomMarkers(const audio_propagation::RoomCoupling& rooms,
                                              const grid::OccupancyMap& map, const std::string& frame) {
  using visualization_msgs::Marker;
  visualization_msgs::MarkerArray out;
  const grid::RoomSegmentation& cut = rooms.segmentation();
  // A square per `stride` cells each way, coloured by the room of its first cell.
  const int stride = grid::CellsAcross(map, 0.25);
  Marker floors = BaseMarker(frame, ros::Time(), "room_floors", 0, Marker::CUBE_LIST);
  floors.scale.x = floors.scale.y = stride * map.resolution();
  floors.scale.z = 0.01;
  // Twelve well-told-apart colours (RGB); rooms past the twelfth reuse them, far apart by number.
  static constexpr float kPalette[12][3] = {{0.12f, 0.47f, 0.71f}, {1.0f, 0.5f, 0.05f}, {0.17f, 0.63f, 0.17f},
                                            {0.84f, 0.15f, 0.16f}, {0.58f, 0.4f, 0.74f}, {0.55f, 0.34f, 0.29f},
                                            {0.89f, 0.47f, 0.76f}, {0.5f, 0.5f, 0.5f},  {0.74f, 0.74f, 0.13f},
                                            {0.09f, 0.75f, 0.81f}, {0.0f, 0.0f, 0.5f},  {0.5f, 0.0f, 0.0f}};
  const auto colour = [](int room) {
    const float* rgb = kPalette[room % 12];
    std_msgs::ColorRGBA c;
    c.r = rgb[0], c.g = rgb[1], c.b = rgb[2], c.a = 0.35f;
    return c;
  };
  for (int j = 0; j < map.height(); j += stride) {
    for (int i = 0; i < map.width(); i += stride) {
      const int room = cut.RoomOfCell(i, j);
      if (room < 0) continue;
      const Eigen::Vector2d centre =
          map.CellCoordsToWorld(Eigen::Vector2d(i + 0.5 * stride, j + 0.5 * stride));
      floors.points.push_back(ToPoint(centre, 0.01));
      floors.colors.push_back(colour(room));
    }
  }
  out.markers.push_back(floors);
  for (std::size_t k = 0; k < cut.rooms().size(); ++k) {
    Marker name = BaseMarker(frame, ros::Time(), "room_names", static_cast<int>(k), Marker::TEXT_VIEW_FACING);
    name.pose.position = ToPoint(cut.rooms()[k].centroid, 0.5);
    name.scale.z = 0.4;
    SetColour(name, 0.1f, 0.1f, 0.1f);
    char text[96];
    std::snprintf(text, sizeof text, "room %zu\nRT60 %.2f s, r_c %.2f m", k, rooms.Acoustics(k).rt60,
                  world_sim::CriticalDistance(rooms.Acoustics(k)));
    name.text = text;
    out.markers.push_back(name);
  }
  for (std::size_t k = 0; k < cut.openings().size(); ++k) {
    const grid::SegmentedOpening& o = cut.openings()[k];
    Marker door = BaseMarker(frame, ros::Time(), "openings", static_cast<int>(k), Marker::SPHERE);
    door.pose.position = ToPoint(o.center, 0.05);
    door.scale.x = door.scale.y = o.width;
    door.scale.z = 0.1;
    SetColour(door, 1.0f, 0.85f, 0.0f, 0.8f);
    out.markers.push_back(door);
  }
  return out;
}

}  // namespace multirobot_audio
