#pragma once

// The channel every experiment runner takes on its command line (sounds_good_experiment,
// local_mutex_sim, charging_experiment), and what it loads:
//   --channel threshold|acoustic  the thesis's hearing threshold, or the acoustic model
//   --profile nava|room           the robots' modem: how long a packet sounds, which table
//   --table FILE                  the decode table (default: the profile's shipped one)
//   --acoustics WORLD.yaml        a world file whose acoustics section the trials get
//   --link-fate [--fate-distance M]  a link's outcome held while neither robot moves M m
//   --directions exact|measured   microphones report the path's exact direction, or what a real
//                                 array reports over the link's DRR and RT60
//   --direction-table FILE        the table of the latter (default: the profile's shipped one)
// The acoustic-only flags are refused with the threshold channel.
#include <memory>
#include <string>
#include <vector>

#include "audio_propagation/audio_channel.h"
#include "audio_propagation/channel_factory.h"
#include "audio_propagation/decode_table.h"
#include "audio_propagation/propagation_model.h"
#include "grid/occupancy_map.h"
#include "nava_modem/modem_profile.h"
#include "tool_args/tool_args.h"
#include "world_sim/world_config.h"

namespace audio_propagation::tools {

inline constexpr const char* kExperimentChannelUsage =
    "[--channel threshold|acoustic] [--profile nava|room] [--table FILE] [--acoustics WORLD.yaml] "
    "[--link-fate [--fate-distance 0.075]] [--directions exact|measured [--direction-table FILE]]";
// The flag that takes no value, for the runner's ToolArgs switches.
inline constexpr const char* kLinkFateSwitch = "--link-fate";

struct ExperimentChannel {
  ChannelModel model = ChannelModel::kThreshold;
  nava_modem::Profile profile = nava_modem::Profile::kNava;
  std::string table_file;      // empty: the profile's shipped table
  std::string acoustics_file;  // empty: each world's own section
  bool measured_directions = false;
  std::string direction_table_file;  // empty: the profile's shipped table
  bool acoustic() const { return model == ChannelModel::kAcoustic; }
};

// Reads the flags above; sets `channel`'s MAC timing from the profile, and its link_fate and
// fate_distance. Fails (UsageError) naming the flag for an unknown channel or profile, a fate
// distance not above 0, or an acoustic-only flag with the threshold channel.
ExperimentChannel ParseExperimentChannel(const multirobot_audio::tools::ToolArgs& args, ChannelOptions& channel);

// The profile's decode table: --table, or the shipped one. Throws grid::InputError naming the file.
std::shared_ptr<const DecodeTable> LoadExperimentTable(const ExperimentChannel& channel);

// With --directions measured, the profile's direction table (--direction-table, or the shipped
// one); else null. Throws grid::InputError naming the file.
std::shared_ptr<const DirectionErrors> LoadExperimentDirections(const ExperimentChannel& channel);

// For the acoustic channel, every world of the run gets the --acoustics file's section, or must
// have one of its own; each is checked against `map` (the trials' map; `map_file` its file, to
// load the acoustics file's world on, empty to load it on its own map). `files[c]` names world c
// in errors ("" for a generated world). Throws grid::InputError naming the file and field.
void GiveAcoustics(const ExperimentChannel& channel, std::vector<world_sim::WorldConfig>& worlds,
                   const std::vector<std::string>& files, const grid::OccupancyMap& map,
                   const std::string& map_file);

// The propagation options the acoustic model judges under: no hearing range unless one was asked
// for (`hearing_given`), and paths down to 30 dB under the quietest world's ambient noise.
void UseAcousticPropagation(PropagationOptions& options, const std::vector<world_sim::WorldConfig>& worlds,
                            bool hearing_given);

}  // namespace audio_propagation::tools
