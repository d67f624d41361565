#include "charging_conversions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <multirobot_audio/LockState.h>

#include "grid/pose2d.h"

namespace multirobot_audio {
namespace {

using local_mutex::State;

// How far the ring's angles may be off before the scan is not world_sim's kind of ring.
constexpr double kRingTolerance = 1e-3;  // rad
constexpr int kRingSegments = 48;
constexpr double kLabelOffset = 0.3;  // m

std_msgs::ColorRGBA Colour(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

std_msgs::ColorRGBA LockColour(State lock, float alpha) {
  switch (lock) {
    case State::kHeld: return Colour(0.1f, 0.85f, 0.2f, alpha);
    case State::kWanted:
    case State::kSilent: return Colour(1.0f, 0.65f, 0.0f, alpha);
    case State::kReleased: break;
  }
  return Colour(0.6f, 0.6f, 0.6f, alpha);
}

visualization_msgs::Marker Disc(const Eigen::Vector2d& at, double diameter, const std_msgs::ColorRGBA& colour) {
  visualization_msgs::Marker m;
  m.type = visualization_msgs::Marker::CYLINDER;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.position.x = at.x();
  m.pose.position.y = at.y();
  m.pose.position.z = 0.02;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = diameter;
  m.scale.z = 0.04;
  m.color = colour;
  return m;
}

}  // namespace

std::vector<charging_demo::ChargerSighting> ToChargerSightings(const multirobot_audio::FiducialArray& msg) {
  std::vector<charging_demo::ChargerSighting> out;
  out.reserve(msg.fiducials.size());
  for (const multirobot_audio::Fiducial& f : msg.fiducials) out.push_back({f.id, f.range, f.bearing});
  return out;
}

std::optional<local_mutex::State> FromLockStateValue(std::uint8_t value) {
  switch (value) {
    case multirobot_audio::LockState::RELEASED: return State::kReleased;
    case multirobot_audio::LockState::WANTED: return State::kWanted;
    case multirobot_audio::LockState::SILENT: return State::kSilent;
    case multirobot_audio::LockState::HELD: return State::kHeld;
    default: return std::nullopt;
  }
}

std::string RingProblem(const sensor_msgs::LaserScan& scan) {
  const std::size_t n = scan.ranges.size();
  char text[200];
  if (n < 3) {
    std::snprintf(text, sizeof text, "%zu readings; expected a ring of at least 3", n);
    return text;
  }
  if (std::abs(grid::NormalizeAngle(scan.angle_min)) > kRingTolerance) {
    std::snprintf(text, sizeof text, "angle_min %.4f rad; expected reading 0 straight ahead (0 rad)",
                  static_cast<double>(scan.angle_min));
    return text;
  }
  const double step = 2.0 * M_PI / static_cast<double>(n);
  if (std::abs(scan.angle_increment - step) * static_cast<double>(n) > kRingTolerance) {
    std::snprintf(text, sizeof text,
                  "angle_increment %.4f rad for %zu readings; expected an even counter-clockwise ring, %.4f rad",
                  static_cast<double>(scan.angle_increment), n, step);
    return text;
  }
  if (!(std::isfinite(scan.range_max) && scan.range_max > 0.0f)) {
    std::snprintf(text, sizeof text, "range_max %g; expected the rangers' reach in m",
                  static_cast<double>(scan.range_max));
    return text;
  }
  return "";
}

multirobot_audio::ChargingState ToChargingState(const charging_demo::ChargingBehaviour& behaviour,
                                                const ChargingStatus& status, double time,
                                                const std::string& odom_frame, const ros::Time& stamp) {
  multirobot_audio::ChargingState msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = odom_frame;
  msg.phase = charging_demo::PhaseName(behaviour.phase());
  msg.phase_time = std::max(0.0, time - behaviour.phase_since());
  msg.lock = static_cast<std::uint8_t>(status.lock);
  msg.want_lock = status.want_lock;
  msg.battery = static_cast<float>(status.battery);
  msg.docked = status.docked;
  msg.charges = behaviour.charges();
  msg.give_ups = behaviour.give_ups();
  msg.redocks = behaviour.redocks();
  msg.forgotten = behaviour.forgotten();
  msg.retraces = status.retraces;
  msg.retracing = status.retracing;
  msg.known_chargers = static_cast<std::uint32_t>(behaviour.known_chargers().size());
  if (const std::optional<Eigen::Vector2d> c = behaviour.charger()) {
    msg.has_charger = true;
    msg.charger.x = c->x();
    msg.charger.y = c->y();
  }
  return msg;
}

visualization_msgs::MarkerArray ToChargerMarkers(const charging_demo::ChargingBehaviour& behaviour,
                                                 const ChargingStatus& status, double wait_distance,
                                                 const std::string& label, const grid::Pose2D& robot,
                                                 const std::string& odom_frame, const ros::Time& stamp) {
  visualization_msgs::MarkerArray out;
  visualization_msgs::Marker clear;
  clear.header.frame_id = odom_frame;
  clear.header.stamp = stamp;
  clear.action = visualization_msgs::Marker::DELETEALL;
  out.markers.push_back(clear);

  auto add = [&](visualization_msgs::Marker m, const std::string& ns, int id) {
    m.header.frame_id = odom_frame;
    m.header.stamp = stamp;
    m.ns = ns;
    m.id = id;
    out.markers.push_back(m);
  };
  int id = 0;
  for (const Eigen::Vector2d& c : behaviour.known_chargers())
    add(Disc(c, 0.3, Colour(0.6f, 0.6f, 0.6f, 0.5f)), "known", id++);

  if (const std::optional<Eigen::Vector2d> c = behaviour.charger()) {
    add(Disc(*c, 0.45, LockColour(status.lock, 0.8f)), "in_use", 0);
    visualization_msgs::Marker ring;
    ring.type = visualization_msgs::Marker::LINE_STRIP;
    ring.action = visualization_msgs::Marker::ADD;
    ring.pose.orientation.w = 1.0;
    ring.scale.x = 0.02;
    ring.color = LockColour(status.lock, 0.8f);
    for (int k = 0; k <= kRingSegments; ++k) {
      const double a = 2.0 * M_PI * k / kRingSegments;
      geometry_msgs::Point p;
      p.x = c->x() + wait_distance * std::cos(a);
      p.y = c->y() + wait_distance * std::sin(a);
      p.z = 0.01;
      ring.points.push_back(p);
    }
    add(ring, "waiting_ring", 0);
  }

  visualization_msgs::Marker text;
  text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
  text.action = visualization_msgs::Marker::ADD;
  // Below the robot on a top-down view, clear of the name world_sim writes above it.
  text.pose.position.x = robot.x;
  text.pose.position.y = robot.y - kLabelOffset;
  text.pose.position.z = 0.3;
  text.pose.orientation.w = 1.0;
  text.scale.z = 0.16;
  text.color = status.lock == State::kReleased ? Colour(0.2f, 0.2f, 0.3f, 1.0f) : LockColour(status.lock, 1.0f);
  char line[160];
  std::snprintf(line, sizeof line, "%s: %s %s %.0f%%", label.c_str(), charging_demo::PhaseName(behaviour.phase()),
                local_mutex::StateName(status.lock), 100.0 * status.battery);
  text.text = line;
  add(text, "label", 0);
  return out;
}

}  // namespace multirobot_audio
