#include "input_checks.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include "conversions.h"
#include "grid/pose2d.h"

namespace multirobot_audio {
namespace {

std::string Is(const std::string& field, double value) {
  char text[64];
  std::snprintf(text, sizeof text, " = %g", value);
  return field + text;
}

// The first non-finite of three numbers named `prefix`.x/y/z.
std::string NonFinite3(const std::string& prefix, double x, double y, double z) {
  if (!std::isfinite(x)) return Is(prefix + ".x", x);
  if (!std::isfinite(y)) return Is(prefix + ".y", y);
  if (!std::isfinite(z)) return Is(prefix + ".z", z);
  return "";
}

std::string TwistFields(const std::string& prefix, const geometry_msgs::Twist& t) {
  std::string p = NonFinite3(prefix + "linear", t.linear.x, t.linear.y, t.linear.z);
  return p.empty() ? NonFinite3(prefix + "angular", t.angular.x, t.angular.y, t.angular.z) : p;
}

}  // namespace

std::string TwistProblem(const geometry_msgs::Twist& msg) { return TwistFields("", msg); }

std::string OdometryProblem(const nav_msgs::Odometry& msg) {
  const geometry_msgs::Pose& pose = msg.pose.pose;
  std::string p = NonFinite3("pose.pose.position", pose.position.x, pose.position.y, pose.position.z);
  if (!p.empty()) return p;
  const geometry_msgs::Quaternion& q = pose.orientation;
  const double norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > 0.01) {
    return Is("pose.pose.orientation: a unit quaternion expected, length", norm);
  }
  if (!grid::IsFinite(FromPose(pose))) return "pose.pose: no finite planar pose";
  return TwistFields("twist.twist.", msg.twist.twist);
}

std::string RobotPosesProblem(const multirobot_audio::RobotPoses& msg) {
  if (msg.names.size() != msg.poses.size()) {
    return "names and poses: one pose per name expected, got " + std::to_string(msg.names.size()) + " names and " +
           std::to_string(msg.poses.size()) + " poses";
  }
  for (std::size_t k = 0; k < msg.poses.size(); ++k) {
    const geometry_msgs::Pose2D& p = msg.poses[k];
    const std::string at = "poses[" + std::to_string(k) + "]";
    if (!std::isfinite(p.x)) return Is(at + ".x", p.x);
    if (!std::isfinite(p.y)) return Is(at + ".y", p.y);
    if (!std::isfinite(p.theta)) return Is(at + ".theta", p.theta);
  }
  return "";
}

std::string ScanProblem(const sensor_msgs::LaserScan& msg) {
  const std::pair<const char*, float> fields[] = {{"angle_min", msg.angle_min},
                                                  {"angle_max", msg.angle_max},
                                                  {"angle_increment", msg.angle_increment},
                                                  {"range_min", msg.range_min},
                                                  {"range_max", msg.range_max}};
  for (const auto& [name, value] : fields) {
    if (!std::isfinite(value)) return Is(name, value);
  }
  if (!(msg.range_max > 0.0f)) return Is("range_max", msg.range_max);
  const std::size_t n = msg.ranges.size();
  if (n > 1 || msg.angle_increment != 0.0f) {
    if (msg.angle_increment == 0.0f) return Is("angle_increment", 0.0);
    const double expected = std::round((msg.angle_max - msg.angle_min) / msg.angle_increment) + 1.0;
    if (std::abs(static_cast<double>(n) - expected) > 1.0) {
      char text[128];
      std::snprintf(text, sizeof text, "ranges: %zu readings, angle_min to angle_max gives %.0f", n, expected);
      return text;
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (msg.ranges[k] < 0.0f && std::isfinite(msg.ranges[k])) return Is("ranges[" + std::to_string(k) + "]", msg.ranges[k]);
  }
  return "";
}

namespace {

// What is wrong with the names of a message that carries one `what` per name.
std::string NamesProblem(const std::vector<std::string>& names, std::size_t items, const std::string& what) {
  if (names.size() != items) {
    return "names and " + what + "s: one " + what + " per name expected, got " + std::to_string(names.size()) +
           " names and " + std::to_string(items) + " " + what + "s";
  }
  std::set<std::string> seen;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (!seen.insert(names[k]).second) return "names[" + std::to_string(k) + "] = '" + names[k] + "': given twice";
  }
  return "";
}

}  // namespace

std::string RobotScansProblem(const multirobot_audio::RobotScans& msg) {
  std::string p = NamesProblem(msg.names, msg.scans.size(), "scan");
  for (std::size_t k = 0; k < msg.scans.size() && p.empty(); ++k) {
    const std::string problem = ScanProblem(msg.scans[k]);
    if (!problem.empty()) p = "scans[" + std::to_string(k) + "] (" + msg.names[k] + ")." + problem;
  }
  return p;
}

std::string RobotCommandsProblem(const multirobot_audio::RobotCommands& msg,
                                 const std::function<bool(const std::string&)>& is_robot) {
  std::string p = NamesProblem(msg.names, msg.commands.size(), "command");
  for (std::size_t k = 0; k < msg.commands.size() && p.empty(); ++k) {
    const std::string at = "commands[" + std::to_string(k) + "] (" + msg.names[k] + ")";
    if (!is_robot(msg.names[k])) return "names[" + std::to_string(k) + "] = '" + msg.names[k] + "': not a robot of the world";
    p = TwistFields(at + ".", msg.commands[k]);
  }
  return p;
}

std::string FiducialsProblem(const multirobot_audio::FiducialArray& msg) {
  for (std::size_t k = 0; k < msg.fiducials.size(); ++k) {
    const multirobot_audio::Fiducial& f = msg.fiducials[k];
    const std::string field = "fiducials[" + std::to_string(k) + "]";
    if (!std::isfinite(f.range) || f.range < 0.0f) return Is(field + ".range", f.range);
    if (!std::isfinite(f.bearing)) return Is(field + ".bearing", f.bearing);
  }
  return "";
}

std::string BatteryProblem(const sensor_msgs::BatteryState& msg) {
  const BatteryReading r = FromBatteryState(msg);
  if (std::isnan(r.level)) return "neither a percentage nor a charge and a positive capacity";
  if (!std::isfinite(r.level) || r.level < 0.0) return Is("level (percentage, or charge / capacity)", r.level);
  return "";
}

std::string ReceptionProblem(const multirobot_audio::AudioReception& msg) {
  using R = multirobot_audio::AudioReception;
  if (msg.kind != R::PACKET && msg.kind != R::NOISE) return Is("kind", msg.kind);
  if (msg.noise > R::COLLISION) return Is("noise", msg.noise);
  if (!std::isfinite(msg.level_db)) return Is("level_db", msg.level_db);
  if (std::isinf(msg.direction)) return Is("direction", msg.direction);
  if (!(msg.direction_confidence >= 0.0f && msg.direction_confidence <= 1.0f)) {
    return Is("direction_confidence", msg.direction_confidence);
  }
  if (!std::isfinite(msg.quality)) return Is("quality", msg.quality);
  if (std::isinf(msg.path_length) || msg.path_length < 0.0f) return Is("path_length", msg.path_length);
  if (std::isinf(msg.path_length_std) || msg.path_length_std < 0.0f) return Is("path_length_std", msg.path_length_std);
  return "";
}

std::string LockStateProblem(const multirobot_audio::LockState& msg) {
  if (msg.state > multirobot_audio::LockState::HELD) return Is("state", msg.state);
  if (!std::isfinite(msg.time_in_state)) return Is("time_in_state", msg.time_in_state);
  return "";
}

std::string PacketProblem(const multirobot_audio::AudioPacket& msg, std::size_t min_bytes, std::size_t max_bytes) {
  if (msg.data.size() >= min_bytes && msg.data.size() <= max_bytes) return "";
  const std::string carried =
      min_bytes == max_bytes ? std::to_string(min_bytes) : std::to_string(min_bytes) + " to " + std::to_string(max_bytes);
  return "data: " + std::to_string(msg.data.size()) + " bytes, the link carries " + carried;
}

std::string JobProblem(const multirobot_audio::Job& msg) {
  return msg.count >= 1 ? "" : "count = 0 (the first job is 1)";
}

}  // namespace multirobot_audio
