#include "conversions.h"

#include <cmath>
#include <cstdint>
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

}  // namespace multirobot_audio
