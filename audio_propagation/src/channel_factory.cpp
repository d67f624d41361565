#include "audio_propagation/channel_factory.h"

#include <algorithm>
#include <sstream>
#include <utility>

#include "audio_propagation/decode_table.h"
#include "audio_propagation/direction_errors_file.h"
#include "grid/input_error.h"
#include "grid/map_file.h"
#include "nava_modem/csma_mac.h"
#include "world_sim/world_file.h"

namespace audio_propagation {
namespace {

// A name that is none of the accepted ones.
[[noreturn]] void Unknown(const std::string& field, const std::string& accepted, const std::string& name) {
  throw ChannelOptionError(field, "expected " + accepted + ", got '" + name + "'");
}

// Throws unless lo <= value <= hi (NaN never is).
void RequireIn(const std::string& field, double value, double lo, double hi) {
  if (value >= lo && value <= hi) return;
  std::ostringstream s;
  s << "expected a number in [" << lo << ", " << hi << "], got " << value;
  throw ChannelOptionError(field, s.str());
}

void RequireWholeIn(const std::string& field, int value, int lo, int hi) {
  if (value >= lo && value <= hi) return;
  throw ChannelOptionError(field, "expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                      "], got " + std::to_string(value));
}

// The modem's timing: the profile's, with nava's bit rate if set.
nava_modem::ModemOptions ModemFor(const SimulatedChannelOptions& o) {
  nava_modem::ModemOptions modem;
  if (o.bit_rate) modem.baud = *o.bit_rate;
  return modem;
}

// The channel's options, the MAC's timing taken from the profile (and the nava bit rate).
ChannelOptions ChannelFor(const SimulatedChannelOptions& o) {
  ChannelOptions c;
  c.capture_margin_db = o.capture_margin_db;
  c.direction_noise = o.direction_noise;
  c.seed = static_cast<std::uint32_t>(o.seed);
  c.cache_size = static_cast<std::size_t>(o.cache_size);
  c.link_fate = o.link_fate;
  c.fate_distance = o.fate_distance;
  nava_modem::UseProfileTiming(o.profile, ModemFor(o), c.mac);
  return c;
}

// The propagation model's options: paths are computed down to `threshold_db`.
PropagationOptions PropagationFor(const SimulatedChannelOptions& o, double threshold_db) {
  PropagationOptions p;
  p.rule = o.rule;
  p.source_level_db = o.source_level_db;
  p.threshold_db = threshold_db;
  p.max_range = o.max_range;
  p.speed_of_sound = o.speed_of_sound;
  return p;
}

// Each robot's microphone: the world's (omni for a robot the world does not have), unless the
// options give one per robot.
std::vector<world_sim::Microphone> MicrophonesFor(const SimulatedChannelOptions& o,
                                                  const std::vector<std::string>& robots,
                                                  const std::vector<world_sim::RobotSpec>& specs) {
  std::vector<world_sim::Microphone> out;
  for (const std::string& name : robots) {
    const auto it = std::find_if(specs.begin(), specs.end(),
                                 [&](const world_sim::RobotSpec& r) { return r.name == name; });
    if (it == specs.end() && !o.world_file.empty()) {
      throw ChannelOptionError("robots", "robot '" + name + "' is not in " + o.world_file);
    }
    out.push_back(it == specs.end() ? world_sim::Microphone::kOmni : it->microphone);
  }
  if (o.microphones.empty()) return out;
  if (o.microphones.size() != robots.size()) {
    throw ChannelOptionError("microphones", "expected one entry per robot (" + std::to_string(robots.size()) +
                                                "), got " + std::to_string(o.microphones.size()));
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    const auto mic = world_sim::ParseMicrophone(o.microphones[k]);
    if (!mic) Unknown("microphones[" + std::to_string(k) + "]", "omni, bidirectional or none", o.microphones[k]);
    out[k] = *mic;
  }
  return out;
}

}  // namespace

const char* ChannelModelName(ChannelModel model) {
  return model == ChannelModel::kAcoustic ? "acoustic" : "threshold";
}

ChannelModel ParseChannelModel(const std::string& name) {
  for (const ChannelModel m : {ChannelModel::kThreshold, ChannelModel::kAcoustic}) {
    if (name == ChannelModelName(m)) return m;
  }
  Unknown("channel_model", kChannelModelNames, name);
}

nava_modem::Profile ParseProfileOption(const std::string& name) {
  const auto profile = nava_modem::ParseProfile(name);
  if (!profile) Unknown("profile", nava_modem::kProfileNames, name);
  return *profile;
}

DiffractionRule ParseRuleOption(const std::string& name) {
  const auto rule = ParseDiffractionRule(name);
  if (!rule) Unknown("rule", "masks or convex_corners", name);
  return *rule;
}

void CheckSimulatedChannelOptions(const SimulatedChannelOptions& o) {
  if (o.world_file.empty() && o.robots.empty()) {
    throw ChannelOptionError("robots", "required (a list of robot names) when world is not set");
  }
  RequireIn("source_level_db", o.source_level_db, -1000.0, 1000.0);
  const double threshold = o.threshold_db.value_or(PropagationOptions{}.threshold_db);
  RequireIn("threshold_db", threshold, -1000.0, 1000.0);
  if (threshold > o.source_level_db) {
    throw ChannelOptionError("threshold_db", "expected at most source_level_db (" + std::to_string(o.source_level_db) +
                                                 "), got " + std::to_string(threshold));
  }
  RequireIn("max_range", o.max_range, 0.0, 1e6);
  RequireIn("speed_of_sound", o.speed_of_sound, 1.0, 1e5);
  RequireIn("capture_margin_db", o.capture_margin_db, 0.0, 1000.0);
  RequireIn("direction_noise", o.direction_noise, 0.0, 10.0);
  if (o.bit_rate) {
    if (o.profile != nava_modem::Profile::kNava) {
      throw ChannelOptionError("bit_rate", std::string("sets the nava profile's bit rate; profile ") +
                                               nava_modem::ProfileName(o.profile) + " has its own timing");
    }
    RequireIn("bit_rate", *o.bit_rate, 1.0, 100000.0);
  }
  try {
    nava_modem::ValidateMacOptions(ChannelFor(o).mac);
  } catch (const std::invalid_argument& e) {
    throw ChannelOptionError("bit_rate", e.what());
  }
  const int rates = nava_modem::ProfileFormat(o.profile).rates;
  RequireWholeIn("rate", o.rate, 0, rates - 1);
  if (o.rate > 0 && o.channel_model == ChannelModel::kAcoustic) {
    throw ChannelOptionError("rate", "the acoustic model's decode tables hold rate 0 only (today's 4-byte packet), got " +
                                         std::to_string(o.rate) + "; use channel_model threshold for faster rates");
  }
  RequireWholeIn("seed", o.seed, 0, 2147483647);
  RequireWholeIn("cache_size", o.cache_size, 0, 10000000);
  if (!(o.fate_distance > 0.0 && o.fate_distance <= 100.0)) {
    std::ostringstream s;
    s << "expected a distance above 0 and at most 100 m (how far a robot moves before a link's fate is drawn again), got "
      << o.fate_distance;
    throw ChannelOptionError("fate_distance", s.str());
  }
  if (o.channel_model != ChannelModel::kAcoustic) {
    if (o.link_fate) throw ChannelOptionError("link_fate", "only used by channel_model acoustic");
    if (!o.decode_table.empty()) throw ChannelOptionError("decode_table", "only used by channel_model acoustic");
    if (!o.delivery_map_robot.empty()) {
      throw ChannelOptionError("delivery_map_robot", "only used by channel_model acoustic");
    }
    if (o.measured_directions) {
      throw ChannelOptionError("directions", "measured needs channel_model acoustic (each link's DRR and RT60)");
    }
  }
  if (o.measured_directions && o.direction_noise > 0.0) {
    throw ChannelOptionError("direction_noise", "unused with directions measured (the table gives each report's error)");
  }
  if (!o.direction_table.empty() && !o.measured_directions) {
    throw ChannelOptionError("direction_table", "only used with directions measured");
  }
}

bool NeedsMap(const SimulatedChannelOptions& o) { return o.world_file.empty() && o.map_file.empty(); }

std::string DecodeTablePath(const SimulatedChannelOptions& o) {
  return o.decode_table.empty() ? ShippedDecodeTable(nava_modem::ProfileName(o.profile)) : o.decode_table;
}

SimulatedChannel BuildSimulatedChannel(const SimulatedChannelOptions& o, std::optional<grid::OccupancyMap> map) {
  CheckSimulatedChannelOptions(o);
  std::vector<world_sim::RobotSpec> specs;
  std::optional<world_sim::Acoustics> acoustics;
  if (!o.world_file.empty()) {
    world_sim::LoadedWorld world = world_sim::LoadWorldFile(o.world_file, o.map_file);
    map = std::move(world.map);
    specs = std::move(world.config.robots);
    acoustics = std::move(world.config.acoustics);
  } else if (!o.map_file.empty()) {
    map = grid::LoadMapFile(o.map_file);
  } else if (!map) {
    throw ChannelOptionError("map", "no world file, no map file and no map given");
  }

  SimulatedChannel out;
  out.robots = o.robots;
  if (out.robots.empty()) {
    for (const world_sim::RobotSpec& r : specs) out.robots.push_back(r.name);
  }
  out.microphones = MicrophonesFor(o, out.robots, specs);
  double threshold = o.threshold_db.value_or(PropagationOptions{}.threshold_db);
  std::optional<DecodeTable> table;
  if (o.channel_model == ChannelModel::kAcoustic) {
    if (!acoustics) {
      throw ChannelOptionError("channel_model", "acoustic needs a world file with an acoustics section; " +
                                                    (o.world_file.empty() ? std::string("no world is set")
                                                                          : o.world_file + " has none"));
    }
    if (!o.delivery_map_robot.empty()) {
      const auto it = std::find(out.robots.begin(), out.robots.end(), o.delivery_map_robot);
      if (it == out.robots.end()) {
        throw ChannelOptionError("delivery_map_robot", "no robot named '" + o.delivery_map_robot + "'");
      }
      out.delivery_robot = static_cast<std::size_t>(it - out.robots.begin());
    }
    // Paths to every listener the model might judge audible, not only to those above the
    // threshold model's default.
    if (!o.threshold_db) threshold = std::min(o.source_level_db, AcousticThresholdDb(*acoustics));
    out.decode_table = DecodeTablePath(o);
    table = LoadDecodeTable(out.decode_table, nava_modem::ProfileName(o.profile));
  }

  out.propagation = std::make_unique<PropagationModel>(std::move(*map), PropagationFor(o, threshold));
  if (table) {
    try {
      out.acoustic = std::make_unique<AcousticModel>(*out.propagation, *acoustics, std::move(*table), out.robots);
    } catch (const std::invalid_argument& e) {
      throw grid::InputError(o.world_file, "", e.what());
    }
  }
  ChannelOptions channel = ChannelFor(o);
  if (o.measured_directions) {
    const std::string profile = nava_modem::ProfileName(o.profile);
    channel.direction_errors = std::make_shared<const DirectionErrors>(
        LoadDirectionErrors(o.direction_table.empty() ? ShippedDirectionErrors(profile) : o.direction_table, profile));
  }
  out.channel = std::make_unique<AudioChannel>(*out.propagation, out.microphones, channel, out.acoustic.get());
  out.profile = o.profile;
  out.modem = ModemFor(o);
  out.rate = o.rate;
  out.format = nava_modem::ProfileFormat(o.profile);
  if (out.acoustic) out.format = nava_modem::FrameFormat{};  // today's packet
  return out;
}

nava_modem::MacFrame SimulatedChannel::Frame(std::vector<std::uint8_t> data) const {
  if (data.size() < format.min_bytes || data.size() > format.max_bytes) {
    throw std::invalid_argument("a frame of " + std::to_string(data.size()) + " bytes: this channel carries " +
                                std::to_string(format.min_bytes) + " to " + std::to_string(format.max_bytes));
  }
  const double airtime = nava_modem::FrameAirtime(profile, modem, data.size(), rate);
  return nava_modem::MacFrame{std::move(data), rate, airtime};
}

}  // namespace audio_propagation
