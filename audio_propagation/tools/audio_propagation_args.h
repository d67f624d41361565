#pragma once

// The command lines of audio_propagation's tools (audio_propagation_query, _bench,
// audio_scene_render, audio_channel_validate), parsed apart from the tools so that tests and the
// fuzzer can call them. Each parser throws multirobot_audio::tools::UsageError naming what it
// refuses, HelpRequested for -h.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/channel_validation.h"
#include "audio_propagation/fate_check.h"
#include "audio_propagation/diffraction_points.h"
#include "nava_modem/modem_profile.h"
#include "tool_args/tool_args.h"

namespace audio_propagation::tools {

struct QueryArgs {
  std::string map_file;
  DiffractionRule rule = DiffractionRule::kMasks;
};
QueryArgs ParseQueryArgs(const std::vector<std::string>& words);

struct BenchArgs {
  std::string map_file;
  int robots = 20, steps = 50;
  unsigned seed = 1;
  DiffractionRule rule = DiffractionRule::kMasks;
  std::string acoustics_file, profile;  // acoustics_file "" for none
  multirobot_audio::tools::ToolUsage usage;  // to refuse a world file without acoustics
};
BenchArgs ParseBenchArgs(const std::vector<std::string>& words);

struct SceneRenderArgs {
  std::string world_file, map_file, scene_file, out, table_file;
  std::optional<nava_modem::Profile> profile;  // none: the scene's own
  double rate = 48000.0;
  unsigned seed = 1;
  std::string rir_dir;  // --rir-dir: measured rooms, for a table measured over them
  multirobot_audio::tools::ToolUsage usage;
};
SceneRenderArgs ParseSceneRenderArgs(const std::vector<std::string>& words);

// ranging_bench: two-way ranging on rendered scenes (tools/ranging_bench.cpp).
struct RangingBenchArgs {
  std::vector<std::string> worlds;  // world files with acoustics
  std::vector<int> teams = {2, 5, 10, 20};  // robots per scene
  int scenes = 2;                   // per world and team size
  int rounds = 2;                   // packets each robot sends in a scene
  nava_modem::Profile profile = nava_modem::Profile::kRoom;
  double rate = 48000.0;
  unsigned seed = 1;
  int threads = 2;
  std::string plot;                 // PNG of the error against distance ("" for none)
  std::string rir_dir;              // --rir-dir: measured rooms, for a table measured over them
  multirobot_audio::tools::ToolUsage usage;
};
RangingBenchArgs ParseRangingBenchArgs(const std::vector<std::string>& words);

struct ValidateArgs {
  std::string world_file, map_file, profile_name, table_file, out;
  ValidationOptions validation;  // links, packets, seed, threads, profile
  // --rir-dir DIR[,DIR...]: measured rooms for a table measured over them (rooms: measured),
  // moved to each link's RT60 and DRR as the table's were to its cells.
  std::string rir_dir;
  // --predict: one link from `from` to `to` at `time` instead of the validation.
  bool predict = false;
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();
  // --static-pairs N: the links' fate (fate_check.h) instead of the validation; --pair-packets,
  // --fate-distance, --seed, --profile.
  int static_pairs = 0;
  FateCheckOptions fate;
  // --rooms: the world's coupled rooms (acoustics.rooms) instead of the validation; with
  // --from X,Y, the reverberant field in each room from a source there.
  bool rooms = false;
  std::optional<Eigen::Vector2d> rooms_from;
  std::string rooms_plot;  // --plot FILE.png (with --from): the level across the map, one field and rooms
  double time = 0.0;
  multirobot_audio::tools::ToolUsage usage;  // to refuse points outside the world's free space
};
ValidateArgs ParseValidateArgs(const std::vector<std::string>& words);

// audio_channel_predict: one link's prediction through a measured response
// (tools/audio_channel_predict.cpp).
struct PredictArgs {
  nava_modem::Profile profile = nava_modem::Profile::kNava;
  std::string rir_file, table_file;
  std::optional<int> channel;  // of the response file (none: it must have one)
  std::string noise;           // white, pink, speech, or a recording's file
  double snr_db = 0.0;
};
PredictArgs ParsePredictArgs(const std::vector<std::string>& words);

// nava_survey: a room's figures from recorded room packets (tools/nava_survey.cpp).
struct SurveyArgs {
  std::vector<std::string> files;  // recordings, one JSON line each
  std::optional<int> channel;      // of each recording (none: mono, or the channels mixed)
  std::optional<double> distance;  // m between the robots while recording
  double source_level_db = 70.0;   // the sender's level at 1 m, in the worlds' dB scale
  std::string world_out;           // --world-out: the acoustics section, "" for none
  std::string response_out;        // --response-out: the estimated response (one recording)
  // --building FILE.yaml: a survey room by room (survey_building.h) instead of `files`; needs
  // --world-out, which then gets a region per room.
  std::string building;
  // --write-train FILE.wav: write what the sending robot plays (no recordings then).
  std::string train_out;
  int train_packets = 10;
  double train_gap = 0.5;  // s, the mean silence between packets
  double train_rate = 48000.0;
  unsigned train_seed = 1;
};
SurveyArgs ParseSurveyArgs(const std::vector<std::string>& words);

}  // namespace audio_propagation::tools
