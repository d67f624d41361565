#pragma once

// A team's simulated audio channel built from one options struct: the world (or a map), the
// robots served and their microphones, the propagation model, the acoustic model with its decode
// table, and the channel itself. The options are named as the audio_propagation node's
// parameters, so that an error naming an option names the parameter too.
#include <cstddef>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/audio_channel.h"
#include "audio_propagation/diffraction_points.h"
#include "audio_propagation/propagation_model.h"
#include "grid/occupancy_map.h"
#include "nava_modem/modem_profile.h"
#include "world_sim/world_config.h"

namespace audio_propagation {

// What decides a packet's fate: the thesis's hearing threshold and capture margin, or the
// world's acoustics and the profile's decode table (acoustic_model.h).
enum class ChannelModel { kThreshold, kAcoustic };
inline const char* kChannelModelNames = "threshold or acoustic";
const char* ChannelModelName(ChannelModel model);

// An option that cannot be used. what() is one line, "<field>: <problem>"; field() is the
// option's name ("microphones[2]" for one entry of a list) and problem() what was expected and
// what was given, so that a caller can name the option its own way (a node: its ~parameter).
class ChannelOptionError : public std::invalid_argument {
 public:
  ChannelOptionError(const std::string& field, const std::string& problem)
      : std::invalid_argument(field + ": " + problem), field_(field), problem_(problem) {}
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string field_, problem_;
};

// The options given by name, each read once: a name that is none of the accepted ones throws
// ChannelOptionError naming the option, the name and the accepted names.
ChannelModel ParseChannelModel(const std::string& name);          // channel_model: threshold | acoustic
nava_modem::Profile ParseProfileOption(const std::string& name);  // profile: nava | room
DiffractionRule ParseRuleOption(const std::string& name);         // rule: masks | convex_corners

struct SimulatedChannelOptions {
  std::string world_file;  // the robots, their microphones, the map and the acoustics
  std::string map_file;    // replaces the world file's map; with neither, the caller gives a map
  std::vector<std::string> robots;       // which robots to serve, in order (default: all the world's)
  std::vector<std::string> microphones;  // one per robot (omni, bidirectional, none), overriding the world's
  nava_modem::Profile profile = nava_modem::Profile::kNava;  // how long a packet sounds; the MAC's unit of time
  std::optional<double> bit_rate;        // bits/s of the nava profile (unset: the profile's own)
  int rate = 0;                          // the profile's rate step every frame goes at
  ChannelModel channel_model = ChannelModel::kThreshold;
  std::string decode_table;        // acoustic model: the table (empty: the profile's shipped one)
  std::string delivery_map_robot;  // acoustic model: the robot whose delivery is to be mapped, if any
  double source_level_db = PropagationOptions{}.source_level_db;  // dB at 1 m
  // The quietest heard (dB); unset, the propagation model's default, or with the acoustic model
  // 30 dB under the world's ambient level (AcousticThresholdDb), if that is lower.
  std::optional<double> threshold_db;
  double max_range = PropagationOptions{}.max_range;  // m; 0 = only the threshold limits
  double speed_of_sound = PropagationOptions{}.speed_of_sound;  // m/s
  DiffractionRule rule = PropagationOptions{}.rule;
  double capture_margin_db = ChannelOptions{}.capture_margin_db;
  double direction_noise = ChannelOptions{}.direction_noise;  // rad, omni microphones
  // Acoustic model: microphones report what a real array does over each link's DRR and RT60
  // (direction_errors.h), from direction_table (empty: the profile's shipped one).
  bool measured_directions = false;
  std::string direction_table;
  int seed = 1;           // back-offs and direction noise
  int cache_size = 1000;  // paths kept for reuse (0: every path computed exactly)
  // Acoustic model: a link's fate held while neither robot moves fate_distance (ChannelOptions).
  bool link_fate = ChannelOptions{}.link_fate;
  double fate_distance = ChannelOptions{}.fate_distance;  // m
};

// Throws ChannelOptionError for: source_level_db or threshold_db outside [-1000, 1000] dB, or
// the threshold above the source level; max_range outside [0, 1e6] m; speed_of_sound outside
// [1, 1e5] m/s; capture_margin_db outside [0, 1000] dB; direction_noise outside [0, 10] rad;
// bit_rate outside [1, 100000] bits/s, given with a profile other than nava, or too fast for
// the MAC; a rate not on the profile's ladder, or above 0 with the acoustic model (its decode
// tables are today's packet's); seed below 0; cache_size outside [0, 10^7]; fate_distance not in
// (0, 100] m; no robots and no world file; decode_table, delivery_map_robot, link_fate,
// measured_directions or direction_table with the threshold model; direction_table without
// measured_directions.
void CheckSimulatedChannelOptions(const SimulatedChannelOptions& options);

// Whether the options name neither a world file nor a map file, so that the caller must give
// the map (the node waits for it on /map).
bool NeedsMap(const SimulatedChannelOptions& options);

// The decode table the acoustic model reads: `decode_table`, or the profile's shipped one.
std::string DecodeTablePath(const SimulatedChannelOptions& options);

// What BuildSimulatedChannel makes. The models are kept behind pointers, so that the channel's
// references to them stay good when this moves.
struct SimulatedChannel {
  std::vector<std::string> robots;                 // served, in the channel's order
  std::vector<world_sim::Microphone> microphones;  // per robot
  std::string decode_table;                        // acoustic model: the table read
  std::optional<std::size_t> delivery_robot;       // acoustic model: delivery_map_robot's index
  std::unique_ptr<PropagationModel> propagation;
  std::unique_ptr<AcousticModel> acoustic;         // acoustic model only
  std::unique_ptr<AudioChannel> channel;           // last: it refers to the models
  // The frames robots may send: the profile's lengths with the threshold model, which judges a
  // frame by its level alone; with the acoustic model today's packet only, as its decode tables
  // were measured on 4-byte packets at rate 0.
  nava_modem::FrameFormat format;
  // `data` as a frame at the options' rate, lasting its airtime on the profile (throws
  // std::invalid_argument for a length outside `format`).
  nava_modem::MacFrame Frame(std::vector<std::uint8_t> data) const;

  nava_modem::Profile profile = nava_modem::Profile::kNava;
  nava_modem::ModemOptions modem;  // the profile's timing (nava's bit rate)
  int rate = 0;
};

// Checks the options (CheckSimulatedChannelOptions) and builds the channel from the world file
// (with map_file's map, if given), else from map_file, else from `map`. Throws
// ChannelOptionError for: no map at all; a robot that is not in the world file; microphones
// not one per robot or naming no microphone; the acoustic model without a world file holding an
// acoustics section; a delivery_map_robot that is not served. Throws grid::InputError naming the
// file for a world, map or decode table that cannot be read or used (a table for another
// profile, acoustics the acoustic model refuses).
SimulatedChannel BuildSimulatedChannel(const SimulatedChannelOptions& options,
                                       std::optional<grid::OccupancyMap> map = std::nullopt);

}  // namespace audio_propagation
