#include "conversions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "world_sim/battery.h"

namespace multirobot_audio {

geometry_msgs::Quaternion ToYawQuaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(0.5 * yaw);
  q.w = std::cos(0.5 * yaw);
  return q;
}

double FromQuaternionYaw(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

grid::Pose2D FromPose(const geometry_msgs::Pose& pose) {
  return {pose.position.x, pose.position.y, FromQuaternionYaw(pose.orientation)};
}

namespace {

// An empty grid: its header and geometry (origin at (x, y), turned by yaw).
nav_msgs::OccupancyGrid EmptyGrid(const std::string& frame, const ros::Time& stamp, double resolution, int width,
                                  int height, const grid::Pose2D& origin) {
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.info.map_load_time = stamp;
  msg.info.resolution = static_cast<float>(resolution);
  msg.info.width = static_cast<std::uint32_t>(width);
  msg.info.height = static_cast<std::uint32_t>(height);
  msg.info.origin.position.x = origin.x;
  msg.info.origin.position.y = origin.y;
  msg.info.origin.orientation = ToYawQuaternion(origin.yaw);
  return msg;
}

}  // namespace

nav_msgs::OccupancyGrid ToOccupancyGrid(const grid::OccupancyMap& map, const std::string& frame,
                                        const ros::Time& stamp) {
  nav_msgs::OccupancyGrid msg = EmptyGrid(frame, stamp, map.resolution(), map.width(), map.height(), map.origin());
  msg.data.reserve(map.cells().size());
  for (grid::Cell c : map.cells()) {
    msg.data.push_back(c == grid::Cell::kFree ? 0 : (c == grid::Cell::kOccupied ? 100 : -1));
  }
  return msg;
}

nav_msgs::OccupancyGrid ToOccupancyGrid(const audio_propagation::DeliveryMap& map, const std::string& frame,
                                        const ros::Time& stamp) {
  nav_msgs::OccupancyGrid msg =
      EmptyGrid(frame, stamp, map.resolution, map.width, map.height, {map.origin.x(), map.origin.y(), 0.0});
  msg.data.reserve(map.probability.size());
  for (double p : map.probability) {
    msg.data.push_back(std::isfinite(p) ? static_cast<std::int8_t>(std::lround(100.0 * std::clamp(p, 0.0, 1.0))) : -1);
  }
  return msg;
}

grid::OccupancyMap FromOccupancyGrid(const nav_msgs::OccupancyGrid& msg) {
  grid::OccupancyMap map(msg.info.width, msg.info.height, msg.info.resolution,
                         {msg.info.origin.position.x, msg.info.origin.position.y,
                          FromQuaternionYaw(msg.info.origin.orientation)});
  if (msg.data.size() != map.cells().size()) {
    throw std::invalid_argument("OccupancyGrid: data has " + std::to_string(msg.data.size()) +
                                " cells, expected width x height = " +
                                std::to_string(map.cells().size()));
  }
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      const int v = msg.data[static_cast<std::size_t>(j) * map.width() + i];
      // map_server's convention: 0 free, 100 occupied, -1 unknown; treat 1..99 by threshold.
      map.set(i, j, v < 0 ? grid::Cell::kUnknown : (v >= 50 ? grid::Cell::kOccupied : grid::Cell::kFree));
    }
  }
  return map;
}

sensor_msgs::LaserScan ToLaserScan(const std::vector<float>& ranges,
                                   const world_sim::RobotModel& model, const std::string& frame,
                                   const ros::Time& stamp) {
  sensor_msgs::LaserScan msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  const double increment = ranges.empty() ? 0.0 : 2.0 * M_PI / ranges.size();
  msg.angle_min = 0.0f;
  msg.angle_increment = static_cast<float>(increment);
  msg.angle_max = static_cast<float>(increment * (ranges.size() - (ranges.empty() ? 0 : 1)));
  msg.range_min = static_cast<float>(model.radius);
  msg.range_max = static_cast<float>(model.radius + model.ir_range);
  msg.ranges = ranges;
  return msg;
}

nav_msgs::Odometry ToOdometry(const grid::Pose2D& pose, double v, double w,
                              const std::string& frame, const std::string& child,
                              const ros::Time& stamp) {
  nav_msgs::Odometry msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.child_frame_id = child;
  msg.pose.pose.position.x = pose.x;
  msg.pose.pose.position.y = pose.y;
  msg.pose.pose.orientation = ToYawQuaternion(pose.yaw);
  msg.twist.twist.linear.x = v;
  msg.twist.twist.angular.z = w;
  return msg;
}

geometry_msgs::TransformStamped ToTransform(const grid::Pose2D& pose, const std::string& parent,
                                            const std::string& child, const ros::Time& stamp) {
  geometry_msgs::TransformStamped t;
  t.header.frame_id = parent;
  t.header.stamp = stamp;
  t.child_frame_id = child;
  t.transform.translation.x = pose.x;
  t.transform.translation.y = pose.y;
  t.transform.rotation = ToYawQuaternion(pose.yaw);
  return t;
}

sensor_msgs::BatteryState ToBatteryState(double level, bool docked,
                                         const world_sim::BatteryModel& model,
                                         const std::string& frame, const ros::Time& stamp) {
  sensor_msgs::BatteryState msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.voltage = static_cast<float>(world_sim::BatteryVoltage(level, model));
  msg.percentage = static_cast<float>(level);
  msg.capacity = static_cast<float>(model.capacity_ah);
  msg.design_capacity = static_cast<float>(model.capacity_ah);
  msg.charge = static_cast<float>(level * model.capacity_ah);
  msg.current = std::numeric_limits<float>::quiet_NaN();
  msg.temperature = std::numeric_limits<float>::quiet_NaN();
  msg.present = true;
  msg.power_supply_technology = sensor_msgs::BatteryState::POWER_SUPPLY_TECHNOLOGY_LION;
  msg.power_supply_health = sensor_msgs::BatteryState::POWER_SUPPLY_HEALTH_GOOD;
  if (docked) {
    msg.power_supply_status = level >= 1.0 ? sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_FULL
                                           : sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_CHARGING;
  } else {
    msg.power_supply_status = sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_DISCHARGING;
  }
  return msg;
}

BatteryReading FromBatteryState(const sensor_msgs::BatteryState& msg) {
  BatteryReading out;
  if (std::isfinite(msg.percentage)) {
    out.level = msg.percentage;
  } else if (std::isfinite(msg.charge) && std::isfinite(msg.capacity) && msg.capacity > 0.0f) {
    out.level = msg.charge / msg.capacity;
  } else {
    out.level = std::numeric_limits<double>::quiet_NaN();
  }
  out.docked = msg.power_supply_status == sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_CHARGING ||
               msg.power_supply_status == sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_FULL;
  return out;
}

multirobot_audio::FiducialArray ToFiducialArray(
    const std::vector<world_sim::FiducialSighting>& seen, const std::string& frame,
    const ros::Time& stamp) {
  multirobot_audio::FiducialArray msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  for (const auto& s : seen) {
    multirobot_audio::Fiducial f;
    f.id = s.id;
    f.range = static_cast<float>(s.range);
    f.bearing = static_cast<float>(s.bearing);
    msg.fiducials.push_back(f);
  }
  return msg;
}

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

namespace {

// What both links' receptions share: the stamp and frame, a packet's data or the noise's kind.
multirobot_audio::AudioReception Heard(const std::string& frame, const ros::Time& stamp, bool packet,
                                       const std::vector<std::uint8_t>& data, int rate, std::uint8_t noise) {
  multirobot_audio::AudioReception msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame;
  if (packet) {
    msg.kind = multirobot_audio::AudioReception::PACKET;
    msg.noise = multirobot_audio::AudioReception::NONE;
    msg.data = data;
    msg.rate = static_cast<std::uint8_t>(rate);
  } else {
    msg.kind = multirobot_audio::AudioReception::NOISE;
    msg.noise = noise;
  }
  return msg;
}

std::uint8_t NoiseKind(nava_modem::RxEvent::Noise noise) {
  switch (noise) {
    case nava_modem::RxEvent::Noise::kZeroByte: return multirobot_audio::AudioReception::ZERO_BYTE;
    case nava_modem::RxEvent::Noise::kOneByte: return multirobot_audio::AudioReception::ONE_BYTE;
    default: return multirobot_audio::AudioReception::BAD_CRC;
  }
}

}  // namespace

multirobot_audio::AudioReception ToAudioReception(const nava_modem::RxEvent& e, const std::string& frame,
                                                  const ros::Time& stamp) {
  multirobot_audio::AudioReception msg =
      Heard(frame, stamp, e.kind == nava_modem::RxEvent::Kind::kPacket, e.data, e.rate, NoiseKind(e.noise));
  msg.level_db = static_cast<float>(e.level_db);
  msg.quality = static_cast<float>(e.quality);
  msg.direction = static_cast<float>(e.direction);
  msg.direction_confidence = static_cast<float>(std::isfinite(e.direction) ? e.direction_confidence : 0.0);
  msg.path_length = std::numeric_limits<float>::quiet_NaN();
  msg.path_length_std = std::numeric_limits<float>::quiet_NaN();
  return msg;
}

multirobot_audio::AudioReception ToAudioReception(const audio_propagation::Reception& rx, const std::string& frame,
                                                  const ros::Time& stamp) {
  // The threshold model knows only collisions; the acoustic model reports what the real
  // receiver would.
  std::uint8_t noise = multirobot_audio::AudioReception::COLLISION;
  if (rx.noise != nava_modem::RxEvent::Noise::kNone) noise = NoiseKind(rx.noise);
  multirobot_audio::AudioReception msg =
      Heard(frame, stamp, rx.kind == audio_propagation::Reception::Kind::kPacket, rx.data, rx.rate, noise);
  msg.level_db = static_cast<float>(rx.level_db);
  msg.direction = static_cast<float>(rx.direction);
  msg.direction_confidence = static_cast<float>(rx.direction_confidence);
  msg.quality = 1.0f;
  msg.path_length = static_cast<float>(rx.path_length);
  msg.path_length_std = std::isfinite(rx.path_length) ? 0.0f : std::numeric_limits<float>::quiet_NaN();
  return msg;
}

visualization_msgs::Marker ToDirectionMarker(double direction, double confidence, bool packet, const std::string& frame,
                                             const ros::Time& stamp, int id) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.header.stamp = stamp;
  m.ns = "direction";
  m.id = id;
  m.type = visualization_msgs::Marker::ARROW;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  const double length = 0.3 + 0.7 * std::clamp(confidence, 0.0, 1.0);
  geometry_msgs::Point tail, head;
  head.x = length * std::cos(direction);
  head.y = length * std::sin(direction);
  m.points = {tail, head};
  m.scale.x = 0.04;  // shaft diameter
  m.scale.y = 0.08;  // head diameter
  m.scale.z = 0.1;   // head length
  m.color.a = 1.0f;
  m.color.r = packet ? 0.1f : 1.0f;
  m.color.g = packet ? 0.8f : 0.5f;
  m.color.b = 0.1f;
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
