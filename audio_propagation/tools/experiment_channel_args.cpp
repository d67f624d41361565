#include "experiment_channel_args.h"

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/direction_errors_file.h"
#include "grid/input_error.h"
#include "world_sim/world_file.h"

namespace audio_propagation::tools {

ExperimentChannel ParseExperimentChannel(const multirobot_audio::tools::ToolArgs& args, ChannelOptions& channel) {
  ExperimentChannel c;
  const std::string model = args.String("--channel", "threshold");
  const std::string profile = args.String("--profile", "nava");
  try {
    c.model = ParseChannelModel(model);
    c.profile = ParseProfileOption(profile);
  } catch (const ChannelOptionError& e) {
    args.Fail((e.field() == "profile" ? "--profile: " : "--channel: ") + e.problem());
  }
  nava_modem::UseProfileTiming(c.profile, {}, channel.mac);
  c.table_file = args.String("--table", "");
  c.acoustics_file = args.String("--acoustics", "");
  const std::string directions = args.String("--directions", "exact");
  if (directions != "exact" && directions != "measured") {
    args.Fail("--directions: expected exact or measured, got " + directions);
  }
  c.measured_directions = directions == "measured";
  c.direction_table_file = args.String("--direction-table", "");
  channel.link_fate = args.Switch(kLinkFateSwitch);
  channel.fate_distance = args.Double("--fate-distance", channel.fate_distance, 1e-6, 100.0);
  const auto given = [&](const char* flag) { return args.given().count(flag) > 0; };
  if (!c.acoustic()) {
    for (const char* flag : {"--table", "--acoustics", kLinkFateSwitch, "--fate-distance", "--directions", "--direction-table"}) {
      if (given(flag)) args.Fail(std::string(flag) + " is for --channel acoustic");
    }
  }
  if (given("--fate-distance") && !channel.link_fate) args.Fail("--fate-distance goes with --link-fate");
  if (given("--direction-table") && !c.measured_directions) args.Fail("--direction-table goes with --directions measured");
  return c;
}

std::shared_ptr<const DecodeTable> LoadExperimentTable(const ExperimentChannel& channel) {
  const std::string name = nava_modem::ProfileName(channel.profile);
  return std::make_shared<const DecodeTable>(
      LoadDecodeTable(channel.table_file.empty() ? ShippedDecodeTable(name) : channel.table_file, name));
}

std::shared_ptr<const DirectionErrors> LoadExperimentDirections(const ExperimentChannel& channel) {
  if (!channel.measured_directions) return nullptr;
  const std::string name = nava_modem::ProfileName(channel.profile);
  return std::make_shared<const DirectionErrors>(LoadDirectionErrors(
      channel.direction_table_file.empty() ? ShippedDirectionErrors(name) : channel.direction_table_file, name));
}

void GiveAcoustics(const ExperimentChannel& channel, std::vector<world_sim::WorldConfig>& worlds,
                   const std::vector<std::string>& files, const grid::OccupancyMap& map,
                   const std::string& map_file) {
  if (!channel.acoustics_file.empty()) {
    const world_sim::LoadedWorld source = world_sim::LoadWorldFile(channel.acoustics_file, map_file);
    if (!source.config.acoustics) {
      throw grid::InputError(channel.acoustics_file, "acoustics", "expected an acoustics section");
    }
    for (world_sim::WorldConfig& w : worlds) w.acoustics = source.config.acoustics;
  }
  for (std::size_t k = 0; k < worlds.size(); ++k) {
    const std::string file = !channel.acoustics_file.empty() ? channel.acoustics_file
                             : k < files.size() && !files[k].empty() ? files[k]
                                                                     : "--acoustics";
    if (!worlds[k].acoustics) {
      throw grid::InputError(file, "acoustics",
                             "--channel acoustic needs an acoustics section (give --acoustics WORLD.yaml)");
    }
    // Only the acoustics are checked here: the world's robots and chargers are the caller's.
    world_sim::WorldConfig acoustics_only;
    acoustics_only.acoustics = worlds[k].acoustics;
    world_sim::ValidateWorld(file, acoustics_only, map);
  }
}

void UseAcousticPropagation(PropagationOptions& options, const std::vector<world_sim::WorldConfig>& worlds,
                            bool hearing_given) {
  for (const world_sim::WorldConfig& w : worlds) {
    if (w.acoustics) UseAcousticPropagation(options, *w.acoustics, hearing_given);
  }
}

}  // namespace audio_propagation::tools
