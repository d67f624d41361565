#include "world_sim/world_file.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <yaml-cpp/yaml.h>

#include "grid/input_error.h"
#include "grid/map_file.h"
#include "grid/yaml_fields.h"
#include "world_sim/collision.h"

namespace world_sim {
namespace {

using grid::YamlFields;

// A number that must lie in [lo, hi] (open at lo when `open_lo`).
double Bounded(const YamlFields& f, const std::string& key, double fallback, double lo, double hi,
               bool open_lo, const std::string& expected) {
  const double v = f.Number(key, fallback);
  const bool ok = std::isfinite(v) && (open_lo ? v > lo : v >= lo) && v <= hi;
  if (!ok) f.Fail(key, "expected " + expected + ", got " + std::to_string(v));
  return v;
}

constexpr double kBig = 1e9;

RobotModel ParseModel(const YamlFields& f) {
  RobotModel m;
  if (!f.Has("robot_model")) return m;
  const YamlFields r = f.Child("robot_model");
  r.ExpectOnlyKeys({"radius", "max_speed", "max_turn_rate", "ir_count", "ir_range",
                    "camera_range", "camera_fov", "odometry", "battery"});
  m.radius = Bounded(r, "radius", m.radius, 0.0, 10.0, true, "a radius in (0, 10] m");
  m.max_speed = Bounded(r, "max_speed", m.max_speed, 0.0, 100.0, true, "a speed in (0, 100] m/s");
  m.max_turn_rate =
      Bounded(r, "max_turn_rate", m.max_turn_rate, 0.0, 100.0, true, "a rate in (0, 100] rad/s");
  const double ir_count = Bounded(r, "ir_count", m.ir_count, 0.0, 360.0, false, "0 to 360 rangers");
  if (ir_count != std::floor(ir_count)) r.Fail("ir_count", "expected a whole number");
  m.ir_count = static_cast<int>(ir_count);
  m.ir_range = Bounded(r, "ir_range", m.ir_range, 0.0, kBig, true, "a positive range in m");
  m.camera_range = Bounded(r, "camera_range", m.camera_range, 0.0, kBig, true, "a positive range in m");
  m.camera_fov = Bounded(r, "camera_fov", m.camera_fov, 0.0, 2.0 * M_PI, true, "an angle in (0, 2 pi] rad");
  if (r.Has("odometry")) {
    const YamlFields o = r.Child("odometry");
    o.ExpectOnlyKeys({"linear", "angular", "heading_bias"});
    m.odometry.linear = Bounded(o, "linear", m.odometry.linear, 0.0, 1.0, false, "a std-dev fraction in [0, 1]");
    m.odometry.angular = Bounded(o, "angular", m.odometry.angular, 0.0, 1.0, false, "a std-dev fraction in [0, 1]");
    m.odometry.heading_bias = Bounded(o, "heading_bias", m.odometry.heading_bias, -1.0, 1.0, false, "rad per metre in [-1, 1]");
  }
  if (r.Has("battery")) {
    const YamlFields b = r.Child("battery");
    b.ExpectOnlyKeys({"idle_drain", "motion_drain", "charge_rate", "empty_voltage", "full_voltage", "capacity_ah"});
    BatteryModel& bm = m.battery;
    bm.idle_drain = Bounded(b, "idle_drain", bm.idle_drain, 0.0, 1.0, false, "a fraction per second in [0, 1]");
    bm.motion_drain = Bounded(b, "motion_drain", bm.motion_drain, 0.0, 1.0, false, "a fraction per metre in [0, 1]");
    bm.charge_rate = Bounded(b, "charge_rate", bm.charge_rate, 0.0, 1.0, false, "a fraction per second in [0, 1]");
    bm.empty_voltage = Bounded(b, "empty_voltage", bm.empty_voltage, 0.0, 1000.0, false, "volts in [0, 1000]");
    bm.full_voltage = Bounded(b, "full_voltage", bm.full_voltage, bm.empty_voltage, 1000.0, true, "volts above empty_voltage");
    bm.capacity_ah = Bounded(b, "capacity_ah", bm.capacity_ah, 0.0, kBig, true, "a positive capacity in Ah");
  }
  return m;
}

grid::Pose2D ReadPose(const YamlFields& f) {
  const std::vector<double> p = f.Numbers("pose", 3, "[x, y, yaw]");
  return {p[0], p[1], p[2]};
}

std::uint32_t ReadId(const YamlFields& f, const std::string& key) {
  const double id = f.Number(key);
  if (id < 0 || id > 4294967295.0 || id != std::floor(id)) {
    f.Fail(key, "expected a whole number from 0 to 4294967295");
  }
  return static_cast<std::uint32_t>(id);
}

}  // namespace

void ValidateWorld(const std::string& file, const WorldConfig& config, const grid::OccupancyMap& map) {
  std::set<std::string> names;
  for (std::size_t k = 0; k < config.robots.size(); ++k) {
    const RobotSpec& r = config.robots[k];
    const std::string field = "robots[" + std::to_string(k) + "]";
    if (!names.insert(r.name).second) {
      throw grid::InputError(file, field + ".name", "duplicate robot name '" + r.name + "'; names must be unique");
    }
    const Eigen::Vector2d c = r.start.position();
    if (!map.IsFreeAt(c)) {
      throw grid::InputError(file, field + ".pose",
                             "robot '" + r.name + "' starts outside the map's free space at (" +
                                 std::to_string(c.x()) + ", " + std::to_string(c.y()) + ")");
    }
    if (DiscHitsWalls(map, c, config.model.radius)) {
      throw grid::InputError(file, field + ".pose",
                             "robot '" + r.name + "' overlaps a wall; expected a pose at least " +
                                 std::to_string(config.model.radius) + " m from walls");
    }
    for (std::size_t q = 0; q < k; ++q) {
      if ((config.robots[q].start.position() - c).norm() < 2.0 * config.model.radius) {
        throw grid::InputError(file, field + ".pose", "robot '" + r.name + "' overlaps robot '" + config.robots[q].name + "'");
      }
    }
  }
  for (std::size_t k = 0; k < config.markers.size(); ++k) {
    const MarkerSpec& m = config.markers[k];
    if (!map.IsFreeAt({m.x, m.y})) {
      throw grid::InputError(file, "markers[" + std::to_string(k) + "].position",
                             "marker " + std::to_string(m.id) + " is inside a wall or off the map; expected a free cell");
    }
  }
  for (std::size_t k = 0; k < config.chargers.size(); ++k) {
    if (!map.IsFreeAt(config.chargers[k].pose.position())) {
      throw grid::InputError(file, "chargers[" + std::to_string(k) + "].pose",
                             "charger is inside a wall or off the map; expected a free cell");
    }
  }
}

LoadedWorld LoadWorldFile(const std::string& path, const std::string& map_override) {
  namespace fs = std::filesystem;
  const YamlFields root = YamlFields::Load(path, "world file");
  root.ExpectOnlyKeys({"map", "seed", "robot_model", "robots", "markers", "chargers"});

  WorldConfig config;
  if (map_override.empty()) {
    fs::path map_path(root.String("map"));
    if (map_path.is_relative()) map_path = fs::path(path).parent_path() / map_path;
    config.map_file = map_path.lexically_normal().string();
  } else {
    config.map_file = map_override;
  }
  const double seed = root.Number("seed", 1.0);
  if (seed < 0 || seed > 4294967295.0 || seed != std::floor(seed)) {
    root.Fail("seed", "expected a whole number from 0 to 4294967295");
  }
  config.seed = static_cast<std::uint32_t>(seed);
  config.model = ParseModel(root);

  for (const YamlFields& r : root.Elements("robots")) {
    r.ExpectOnlyKeys({"name", "pose", "microphone", "battery"});
    RobotSpec spec;
    spec.name = r.String("name");
    if (spec.name.empty() || spec.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") != std::string::npos ||
        !std::isalpha(static_cast<unsigned char>(spec.name[0]))) {
      r.Fail("name", "expected a ROS name (a letter, then letters, digits or _), got '" + spec.name + "'");
    }
    spec.start = ReadPose(r);
    const std::string mic = r.String("microphone", "omni");
    const auto parsed = ParseMicrophone(mic);
    if (!parsed) r.Fail("microphone", "expected omni, bidirectional or none, got '" + mic + "'");
    spec.microphone = *parsed;
    spec.battery = Bounded(r, "battery", 1.0, 0.0, 1.0, false, "a level in [0, 1]");
    config.robots.push_back(spec);
  }
  if (config.robots.empty()) root.Fail("robots", "expected a list of at least one robot");

  for (const YamlFields& m : root.Elements("markers")) {
    m.ExpectOnlyKeys({"id", "position"});
    const std::vector<double> p = m.Numbers("position", 2, "[x, y]");
    config.markers.push_back({ReadId(m, "id"), p[0], p[1]});
  }
  for (const YamlFields& c : root.Elements("chargers")) {
    c.ExpectOnlyKeys({"pose", "radius", "marker"});
    ChargerSpec spec;
    spec.pose = ReadPose(c);
    spec.radius = Bounded(c, "radius", spec.radius, 0.0, 100.0, true, "a radius in (0, 100] m");
    if (c.Has("marker")) spec.marker = ReadId(c, "marker");
    config.chargers.push_back(spec);
  }

  grid::OccupancyMap map;
  try {
    map = grid::LoadMapFile(config.map_file);
  } catch (const grid::InputError& e) {
    throw grid::InputError(path, "map", std::string("cannot load the map: ") + e.what());
  }
  ValidateWorld(path, config, map);
  return {config, std::move(map)};
}

}  // namespace world_sim

namespace world_sim {
namespace {

void EmitPose(YAML::Emitter& out, const grid::Pose2D& p) {
  out << YAML::Flow << YAML::BeginSeq << p.x << p.y << p.yaw << YAML::EndSeq;
}

void EmitModel(YAML::Emitter& out, const RobotModel& m) {
  out << YAML::Key << "robot_model" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "radius" << YAML::Value << m.radius;
  out << YAML::Key << "max_speed" << YAML::Value << m.max_speed;
  out << YAML::Key << "max_turn_rate" << YAML::Value << m.max_turn_rate;
  out << YAML::Key << "ir_count" << YAML::Value << m.ir_count;
  out << YAML::Key << "ir_range" << YAML::Value << m.ir_range;
  out << YAML::Key << "camera_range" << YAML::Value << m.camera_range;
  out << YAML::Key << "camera_fov" << YAML::Value << m.camera_fov;
  out << YAML::Key << "odometry" << YAML::Value << YAML::Flow << YAML::BeginMap
      << YAML::Key << "linear" << YAML::Value << m.odometry.linear
      << YAML::Key << "angular" << YAML::Value << m.odometry.angular
      << YAML::Key << "heading_bias" << YAML::Value << m.odometry.heading_bias << YAML::EndMap;
  const BatteryModel& b = m.battery;
  out << YAML::Key << "battery" << YAML::Value << YAML::Flow << YAML::BeginMap
      << YAML::Key << "idle_drain" << YAML::Value << b.idle_drain
      << YAML::Key << "motion_drain" << YAML::Value << b.motion_drain
      << YAML::Key << "charge_rate" << YAML::Value << b.charge_rate
      << YAML::Key << "empty_voltage" << YAML::Value << b.empty_voltage
      << YAML::Key << "full_voltage" << YAML::Value << b.full_voltage
      << YAML::Key << "capacity_ah" << YAML::Value << b.capacity_ah << YAML::EndMap;
  out << YAML::EndMap;
}

}  // namespace

void SaveWorldFile(const std::string& path, const WorldConfig& config) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);  // enough digits to read back every double exactly
  out << YAML::BeginMap;
  // Absolute, so the file can be loaded from wherever it is written.
  out << YAML::Key << "map" << YAML::Value
      << std::filesystem::absolute(config.map_file).lexically_normal().string();
  out << YAML::Key << "seed" << YAML::Value << config.seed;
  EmitModel(out, config.model);
  out << YAML::Key << "robots" << YAML::Value << YAML::BeginSeq;
  for (const RobotSpec& r : config.robots) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << r.name
        << YAML::Key << "pose" << YAML::Value;
    EmitPose(out, r.start);
    out << YAML::Key << "microphone" << YAML::Value << MicrophoneName(r.microphone)
        << YAML::Key << "battery" << YAML::Value << r.battery << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "markers" << YAML::Value << YAML::BeginSeq;
  for (const MarkerSpec& m : config.markers)
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "id" << YAML::Value << m.id
        << YAML::Key << "position" << YAML::Value << YAML::Flow << YAML::BeginSeq << m.x << m.y
        << YAML::EndSeq << YAML::EndMap;
  out << YAML::EndSeq;
  out << YAML::Key << "chargers" << YAML::Value << YAML::BeginSeq;
  for (const ChargerSpec& c : config.chargers) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "pose" << YAML::Value;
    EmitPose(out, c.pose);
    out << YAML::Key << "radius" << YAML::Value << c.radius;
    if (c.marker) out << YAML::Key << "marker" << YAML::Value << *c.marker;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  std::ofstream file(path);
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error(path + ": cannot write the world file");
}

}  // namespace world_sim
