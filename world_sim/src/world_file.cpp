#include "world_sim/world_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <yaml-cpp/yaml.h>

#include "grid/file_path.h"
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


RoomAcoustics ParseRoom(const YamlFields& f, RoomAcoustics room) {
  room.rt60 = Bounded(f, "rt60", room.rt60, 0.0, 10.0, true, "a reverberation time in (0, 10] s");
  room.volume = Bounded(f, "volume", room.volume, 0.0, kBig, false, "a volume in m^3 (>= 0)");
  room.critical_distance =
      Bounded(f, "critical_distance", room.critical_distance, 0.0, 1000.0, false, "a distance in [0, 1000] m");
  if (room.volume == 0.0 && room.critical_distance == 0.0) {
    f.Fail("volume", "expected a room volume (m^3) or a critical_distance (m) above 0");
  }
  return room;
}

NoiseKind ReadNoiseKind(const YamlFields& f, const std::string& key, NoiseKind fallback) {
  const std::string name = f.String(key, NoiseKindName(fallback));
  const auto kind = ParseNoiseKind(name);
  if (!kind) f.Fail(key, std::string("expected ") + kNoiseKindNames + ", got '" + name + "'");
  return *kind;
}

// `root` is the world file's, whose folder a recording's relative path starts from.
std::optional<Acoustics> ParseAcoustics(const YamlFields& root, const std::string& path) {
  if (!root.Has("acoustics")) return std::nullopt;
  const YamlFields f = root.Child("acoustics");
  f.ExpectOnlyKeys({"rt60", "volume", "critical_distance", "ambient_db", "ambient_kind", "corner_loss_db",
                    "regions", "noise_sources", "rooms"});
  Acoustics a;
  a.room = ParseRoom(f, a.room);
  a.ambient_db = Bounded(f, "ambient_db", a.ambient_db, -50.0, 150.0, false, "a level in [-50, 150] dB");
  a.ambient_kind = ReadNoiseKind(f, "ambient_kind", a.ambient_kind);
  if (a.ambient_kind == NoiseKind::kWhine || a.ambient_kind == NoiseKind::kRecording) {
    f.Fail("ambient_kind", "expected white, pink or speech; a whine or a recording needs a source");
  }
  a.corner_loss_db = Bounded(f, "corner_loss_db", a.corner_loss_db, 0.0, 60.0, false, "a loss in [0, 60] dB per corner");
  for (const YamlFields& r : f.Elements("regions")) {
    r.ExpectOnlyKeys({"name", "box", "rt60", "volume", "critical_distance"});
    AcousticRegion region;
    region.name = r.String("name");
    const std::vector<double> box = r.Numbers("box", 4, "[min_x, min_y, max_x, max_y]");
    if (!(box[0] < box[2] && box[1] < box[3])) {
      r.Fail("box", "expected min_x < max_x and min_y < max_y");
    }
    region.min_x = box[0], region.min_y = box[1], region.max_x = box[2], region.max_y = box[3];
    RoomAcoustics blank;
    blank.rt60 = a.room.rt60;
    region.room = ParseRoom(r, blank);
    a.regions.push_back(region);
  }
  if (f.Has("rooms")) {
    const YamlFields r = f.Child("rooms");
    r.ExpectOnlyKeys({"ceiling_height", "door_height", "door_half_width", "min_room_area", "max_obstacle_size",
                      "corridor_elongation"});
    CoupledRoomsSpec rooms;
    rooms.ceiling_height =
        Bounded(r, "ceiling_height", rooms.ceiling_height, 0.0, 100.0, true, "a height in (0, 100] m");
    rooms.door_height = Bounded(r, "door_height", rooms.door_height, 0.0, rooms.ceiling_height, true,
                                "a height in (0, ceiling_height = " + std::to_string(rooms.ceiling_height) + "] m");
    rooms.door_half_width =
        Bounded(r, "door_half_width", rooms.door_half_width, 0.0, 50.0, true, "a half-width in (0, 50] m");
    rooms.min_room_area =
        Bounded(r, "min_room_area", rooms.min_room_area, 0.0, kBig, false, "an area in m^2 (>= 0)");
    rooms.max_obstacle_size =
        Bounded(r, "max_obstacle_size", rooms.max_obstacle_size, 0.0, kBig, false, "a length in m (>= 0)");
    rooms.corridor_elongation = Bounded(r, "corridor_elongation", rooms.corridor_elongation, 0.0, kBig, false,
                                        "0 (rooms kept whole) or a ratio of length to width >= 1");
    if (rooms.corridor_elongation > 0.0 && rooms.corridor_elongation < 1.0) {
      r.Fail("corridor_elongation", "0 (rooms kept whole) or a ratio of length to width >= 1, got " +
                                        std::to_string(rooms.corridor_elongation));
    }
    a.rooms = rooms;
  }
  std::size_t k = 0;
  for (const YamlFields& n : f.Elements("noise_sources")) {
    n.ExpectOnlyKeys({"name", "position", "robot", "level_db", "kind", "frequency", "file", "duty", "period", "phase"});
    NoiseSourceSpec s;
    s.name = n.String("name", "noise_" + std::to_string(k++));
    if (n.Has("robot") == n.Has("position")) {
      n.Fail("position", "expected either a position [x, y] or a robot name, not both nor neither");
    }
    if (n.Has("position")) {
      const std::vector<double> p = n.Numbers("position", 2, "[x, y]");
      s.x = p[0], s.y = p[1];
    } else {
      s.robot = n.String("robot");
    }
    s.level_db = Bounded(n, "level_db", s.level_db, -50.0, 150.0, false, "a level at 1 m in [-50, 150] dB");
    s.kind = ReadNoiseKind(n, "kind", s.kind);
    s.frequency = Bounded(n, "frequency", 0.0, 0.0, 20000.0, false, "a frequency in [0, 20000] Hz");
    if (s.kind == NoiseKind::kWhine && s.frequency <= 0.0) n.Fail("frequency", "expected a whine's frequency above 0 Hz");
    if ((s.kind == NoiseKind::kRecording) != n.Has("file")) {
      n.Fail("file", s.kind == NoiseKind::kRecording ? "expected the recording's audio file"
                                                     : "expected only with kind: recording");
    }
    if (n.Has("file")) {
      std::filesystem::path file(n.String("file"));
      if (file.is_relative()) file = std::filesystem::path(path).parent_path() / file;
      std::string why;
      if (!grid::IsRegularFile(file.string(), &why)) n.Fail("file", why + ": " + file.string());
      s.file = grid::CanonicalPath(file.string());
    }
    s.duty = Bounded(n, "duty", s.duty, 0.0, 1.0, true, "a duty cycle in (0, 1]");
    s.period = Bounded(n, "period", s.period, 0.0, kBig, true, "a period above 0 s");
    s.phase = Bounded(n, "phase", s.phase, -kBig, kBig, false, "a phase in s");
    a.noise_sources.push_back(s);
  }
  return a;
}

// Whether a region's box holds the centre of a free cell of `map`.
bool CoversFreeSpace(const AcousticRegion& region, const grid::OccupancyMap& map) {
  // The box clipped to the map's extent in the world (an infinite box is the whole map), then
  // its corners in cells, clamped to the map before any conversion to int (a box far off the
  // map must not overflow the index); a rotated map's box is searched whole.
  double extent[4] = {1e300, 1e300, -1e300, -1e300};
  for (const double i : {0.0, static_cast<double>(map.width())}) {
    for (const double j : {0.0, static_cast<double>(map.height())}) {
      const Eigen::Vector2d w = map.CellCoordsToWorld({i, j});
      extent[0] = std::min(extent[0], w.x()), extent[1] = std::min(extent[1], w.y());
      extent[2] = std::max(extent[2], w.x()), extent[3] = std::max(extent[3], w.y());
    }
  }
  const double x0 = std::clamp(region.min_x, extent[0], extent[2]), x1 = std::clamp(region.max_x, extent[0], extent[2]);
  const double y0 = std::clamp(region.min_y, extent[1], extent[3]), y1 = std::clamp(region.max_y, extent[1], extent[3]);
  int lo[2] = {map.width(), map.height()}, hi[2] = {-1, -1};
  for (const double x : {x0, x1}) {
    for (const double y : {y0, y1}) {
      const Eigen::Vector2d c = map.WorldToCellCoords({x, y});
      for (int d = 0; d < 2; ++d) {
        const double limit = d == 0 ? map.width() - 1 : map.height() - 1;
        const int v = std::isfinite(c[d]) ? static_cast<int>(std::clamp(std::floor(c[d]), 0.0, limit)) : 0;
        lo[d] = std::min(lo[d], v), hi[d] = std::max(hi[d], v);
      }
    }
  }
  for (int j = lo[1]; j <= hi[1]; ++j) {
    for (int i = lo[0]; i <= hi[0]; ++i) {
      const Eigen::Vector2d c = map.CellCenter(i, j);
      if (!map.Blocks(i, j) && region.Contains(c.x(), c.y())) return true;
    }
  }
  return false;
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
  if (config.acoustics) {
    const Acoustics& a = *config.acoustics;
    for (std::size_t k = 0; k < a.regions.size(); ++k) {
      if (!CoversFreeSpace(a.regions[k], map)) {
        const AcousticRegion& r = a.regions[k];
        throw grid::InputError(file, "acoustics.regions[" + std::to_string(k) + "].box",
                               "region '" + r.name + "' [" + std::to_string(r.min_x) + ", " + std::to_string(r.min_y) +
                                   ", " + std::to_string(r.max_x) + ", " + std::to_string(r.max_y) +
                                   "] covers none of the map's free space");
      }
    }
    if (a.rooms && a.rooms->door_half_width < map.resolution()) {
      throw grid::InputError(file, "acoustics.rooms.door_half_width",
                             "expected at least one cell of the map (" + std::to_string(map.resolution()) +
                                 " m), got " + std::to_string(a.rooms->door_half_width));
    }
    for (std::size_t k = 0; k < a.noise_sources.size(); ++k) {
      const NoiseSourceSpec& s = a.noise_sources[k];
      const std::string field = "acoustics.noise_sources[" + std::to_string(k) + "]";
      if (!s.robot.empty()) {
        if (!names.count(s.robot)) {
          throw grid::InputError(file, field + ".robot", "no robot named '" + s.robot + "' in this world");
        }
      } else if (!map.IsFreeAt({s.x, s.y})) {
        throw grid::InputError(file, field + ".position",
                               "noise source '" + s.name + "' at (" + std::to_string(s.x) + ", " +
                                   std::to_string(s.y) + ") is inside a wall or off the map; expected a free cell");
      }
    }
  }
}

LoadedWorld LoadWorldFile(const std::string& path, const std::string& map_override) {
  namespace fs = std::filesystem;
  const YamlFields root = YamlFields::Load(path, "world file");
  root.ExpectOnlyKeys({"map", "seed", "robot_model", "robots", "markers", "chargers", "acoustics"});

  WorldConfig config;
  if (map_override.empty()) {
    fs::path map_path(root.String("map"));
    if (map_path.is_relative()) map_path = fs::path(path).parent_path() / map_path;
    config.map_file = grid::CanonicalPath(map_path.string());
  } else {
    config.map_file = grid::CanonicalPath(map_override);
  }
  const double seed = root.Number("seed", 1.0);
  if (seed < 0 || seed > 4294967295.0 || seed != std::floor(seed)) {
    root.Fail("seed", "expected a whole number from 0 to 4294967295");
  }
  config.seed = static_cast<std::uint32_t>(seed);
  config.model = ParseModel(root);
  config.acoustics = ParseAcoustics(root, path);

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


void EmitRoom(YAML::Emitter& out, const RoomAcoustics& r) {
  out << YAML::Key << "rt60" << YAML::Value << r.rt60 << YAML::Key << "volume" << YAML::Value << r.volume
      << YAML::Key << "critical_distance" << YAML::Value << r.critical_distance;
}

void EmitAcoustics(YAML::Emitter& out, const Acoustics& a) {
  out << YAML::Key << "acoustics" << YAML::Value << YAML::BeginMap;
  EmitRoom(out, a.room);
  out << YAML::Key << "ambient_db" << YAML::Value << a.ambient_db << YAML::Key << "ambient_kind" << YAML::Value
      << NoiseKindName(a.ambient_kind) << YAML::Key << "corner_loss_db" << YAML::Value << a.corner_loss_db;
  out << YAML::Key << "regions" << YAML::Value << YAML::BeginSeq;
  for (const AcousticRegion& r : a.regions) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << r.name << YAML::Key << "box"
        << YAML::Value << YAML::Flow << YAML::BeginSeq << r.min_x << r.min_y << r.max_x << r.max_y << YAML::EndSeq;
    EmitRoom(out, r.room);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  if (a.rooms) {
    out << YAML::Key << "rooms" << YAML::Value << YAML::BeginMap << YAML::Key << "ceiling_height" << YAML::Value
        << a.rooms->ceiling_height << YAML::Key << "door_height" << YAML::Value << a.rooms->door_height << YAML::Key
        << "door_half_width" << YAML::Value << a.rooms->door_half_width << YAML::Key << "min_room_area"
        << YAML::Value << a.rooms->min_room_area << YAML::Key << "max_obstacle_size" << YAML::Value
        << a.rooms->max_obstacle_size << YAML::Key << "corridor_elongation" << YAML::Value
        << a.rooms->corridor_elongation << YAML::EndMap;
  }
  out << YAML::Key << "noise_sources" << YAML::Value << YAML::BeginSeq;
  for (const NoiseSourceSpec& s : a.noise_sources) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << s.name;
    if (s.robot.empty()) {
      out << YAML::Key << "position" << YAML::Value << YAML::Flow << YAML::BeginSeq << s.x << s.y << YAML::EndSeq;
    } else {
      out << YAML::Key << "robot" << YAML::Value << s.robot;
    }
    out << YAML::Key << "level_db" << YAML::Value << s.level_db << YAML::Key << "kind" << YAML::Value
        << NoiseKindName(s.kind) << YAML::Key << "frequency" << YAML::Value << s.frequency;
    if (s.kind == NoiseKind::kRecording) out << YAML::Key << "file" << YAML::Value << s.file;
    out << YAML::Key << "duty"
        << YAML::Value << s.duty << YAML::Key << "period" << YAML::Value << s.period << YAML::Key << "phase"
        << YAML::Value << s.phase << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
}

}  // namespace

void SaveWorldFile(const std::string& path, const WorldConfig& config) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);  // enough digits to read back every double exactly
  out << YAML::BeginMap;
  // Absolute, so the file can be loaded from wherever it is written.
  out << YAML::Key << "map" << YAML::Value << grid::CanonicalPath(config.map_file);
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
  out << YAML::EndSeq;
  if (config.acoustics) EmitAcoustics(out, *config.acoustics);
  out << YAML::EndMap;
  std::ofstream file(path);
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error(path + ": cannot write the world file");
}

}  // namespace world_sim
