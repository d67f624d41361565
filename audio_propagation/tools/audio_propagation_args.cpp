#include "audio_propagation_args.h"

#include <cmath>
#include <sstream>

#include "nava_modem/modem_options.h"
#include "package_data/package_data.h"

namespace audio_propagation::tools {
namespace {

using multirobot_audio::tools::ToolArgs;

DiffractionRule Rule(const ToolArgs& args, const std::string& name) {
  const auto rule = ParseDiffractionRule(name);
  if (!rule) args.Fail("--rule: expected masks or convex_corners, got " + name);
  return *rule;
}

nava_modem::Profile Profile(const ToolArgs& args, const std::string& name) {
  const auto profile = nava_modem::ParseProfile(name);
  if (!profile) args.Fail(std::string("--profile: expected ") + nava_modem::kProfileNames + ", got " + name);
  return *profile;
}

Eigen::Vector2d ParsePoint(const ToolArgs& args, const std::string& text) {
  std::istringstream in(text);
  double x = 0.0, y = 0.0;
  char comma = 0;
  std::string rest;
  if (!(in >> x >> comma >> y) || comma != ',' || (in >> rest) || !std::isfinite(x) || !std::isfinite(y)) {
    args.Fail("--predict: expected two points X1,Y1 X2,Y2 in m, got '" + text + "'");
  }
  return {x, y};
}

// --channel K of an audio file (0-based), if given.
std::optional<int> ChannelArg(const ToolArgs& args) {
  if (args.String("--channel", "").empty()) return std::nullopt;
  return static_cast<int>(args.Int("--channel", 0, 0, 1023));
}

}  // namespace

QueryArgs ParseQueryArgs(const std::vector<std::string>& words) {
  const ToolArgs args("audio_propagation_query",
                      "audio_propagation_query --map MAP.yaml [--rule masks|convex_corners] < queries", words);
  QueryArgs q;
  q.map_file = args.Required("--map");
  const std::string rule_name = args.String("--rule", "masks");
  args.CheckAllUsed();
  q.rule = Rule(args, rule_name);
  return q;
}

BenchArgs ParseBenchArgs(const std::vector<std::string>& words) {
  const ToolArgs args(
      "audio_propagation_bench",
      "audio_propagation_bench --map MAP.yaml [--robots N] [--steps K] [--seed S] [--rule masks|convex_corners]\n"
      "                        [--acoustics WORLD.yaml [--profile nava|room]]",
      words);
  BenchArgs b;
  b.usage = args.tool_usage();
  b.map_file = args.Required("--map");
  b.robots = static_cast<int>(args.Int("--robots", 20, 2, 100000));
  b.steps = static_cast<int>(args.Int("--steps", 50, 1, 1000000));
  b.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  const std::string rule_name = args.String("--rule", "masks");
  b.acoustics_file = args.String("--acoustics", "");
  b.profile = args.String("--profile", "nava");
  args.CheckAllUsed();
  b.rule = Rule(args, rule_name);
  return b;
}

SceneRenderArgs ParseSceneRenderArgs(const std::vector<std::string>& words) {
  const ToolArgs args(
      "audio_scene_render",
      "audio_scene_render --world W [--map M] --scene S --out DIR [--profile nava|room] [--rate 48000] "
      "[--table FILE] [--seed 1] [--rir-dir DIR[,DIR...]]",
      words);
  SceneRenderArgs s;
  s.usage = args.tool_usage();
  s.rir_dir = args.String("--rir-dir", "");
  s.world_file = args.Required("--world");
  s.map_file = args.String("--map", "");
  s.scene_file = args.Required("--scene");
  s.out = args.Required("--out");
  const std::string profile_name = args.String("--profile", "");
  s.rate = args.Double("--rate", 48000.0, nava_modem::kMinSampleRate, nava_modem::kMaxSampleRate);
  s.table_file = args.String("--table", "");
  s.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  args.CheckAllUsed();
  if (!profile_name.empty()) s.profile = Profile(args, profile_name);
  return s;
}

PredictArgs ParsePredictArgs(const std::vector<std::string>& words) {
  const ToolArgs args("audio_channel_predict",
                      "audio_channel_predict --profile nava|room --rir FILE.wav [--channel K] "
                      "--noise white|pink|speech|FILE.wav --snr-db X [--table FILE]",
                      words);
  PredictArgs p;
  p.profile = Profile(args, args.Required("--profile"));
  p.rir_file = args.Required("--rir");
  p.channel = ChannelArg(args);
  p.noise = args.Required("--noise");
  p.snr_db = args.Double("--snr-db", 0.0, -100.0, 100.0);
  if (args.String("--snr-db", "").empty()) args.Fail("--snr-db is required");
  p.table_file = args.String("--table", "");
  args.CheckAllUsed();
  return p;
}

SurveyArgs ParseSurveyArgs(const std::vector<std::string>& words) {
  const ToolArgs args("nava_survey",
                      "nava_survey [--profile room] [--channel K] [--distance M [--source-level-db 70] "
                      "[--world-out FILE.yaml]] [--response-out FILE.wav] RECORDING.wav... | "
                      "nava_survey [--channel K] --building SURVEY.yaml --world-out FILE.yaml | "
                      "nava_survey --write-train FILE.wav [--packets 10] [--gap 0.5] [--rate 48000] [--seed 1]",
                      words);
  SurveyArgs s;
  s.train_out = args.String("--write-train", "");
  if (!s.train_out.empty()) {
    s.train_packets = static_cast<int>(args.Int("--packets", s.train_packets, 1, 1000));
    s.train_gap = args.Double("--gap", s.train_gap, 0.0, 60.0);
    s.train_rate = args.Double("--rate", s.train_rate, 1.0, 1e6);
    s.train_seed = static_cast<unsigned>(args.Int("--seed", s.train_seed, 0, 1000000));
    if (!args.positional().empty()) args.Fail("--write-train writes the packets to play; it takes no recordings");
    args.CheckAllUsed();
    return s;
  }
  if (const std::string profile = args.String("--profile", "room"); profile != "room") {
    args.Fail("--profile " + profile + ": a survey needs the room profile's packets (nava's two tones do not cover "
              "the 600-5400 Hz a response is measured in)");
  }
  s.channel = ChannelArg(args);
  if (!args.String("--distance", "").empty()) s.distance = args.Double("--distance", 1.0, 0.01, 1000.0);
  s.source_level_db = args.Double("--source-level-db", s.source_level_db, -1000.0, 1000.0);
  s.world_out = args.String("--world-out", "");
  s.response_out = args.String("--response-out", "");
  s.files = args.positional();
  s.building = args.String("--building", "");
  if (!s.building.empty()) {
    if (!s.files.empty()) args.Fail("--building names the recordings room by room; it takes none besides");
    if (s.distance || !args.String("--source-level-db", "").empty()) {
      args.Fail("--building: the survey file gives each room's distance and the source level");
    }
    if (s.world_out.empty()) args.Fail("--building needs --world-out: the world's acoustics, a region a room");
    if (!s.response_out.empty()) args.Fail("--response-out takes one recording");
    args.CheckAllUsed();
    return s;
  }
  if (s.files.empty()) args.Fail("expected at least one recording");
  if (!s.world_out.empty() && !s.distance) {
    args.Fail("--world-out needs --distance: the robots' distance turns the DRR into a critical distance and the "
              "noise into the world's dB scale");
  }
  if (!args.String("--source-level-db", "").empty() && !s.distance) args.Fail("--source-level-db needs --distance");
  if (!s.response_out.empty() && s.files.size() != 1) args.Fail("--response-out takes one recording");
  args.CheckAllUsed();
  return s;
}

ValidateArgs ParseValidateArgs(const std::vector<std::string>& words) {
  const ToolArgs args(
      "audio_channel_validate",
      "audio_channel_validate --world W [--map M] [--profile nava|room] [--links 300] [--packets 4] [--table FILE] "
      "[--seed 1] [--out DIR] [--threads 2] [--rir-dir DIR[,DIR...]] | --world W [--map M] [--profile P] [--table FILE] [--time 0] "
      "--predict X1,Y1 X2,Y2 | --world W [--map M] [--profile P] [--table FILE] [--seed 1] --static-pairs N "
      "[--pair-packets 30] [--fate-distance 0.075] | --world W [--map M] --rooms [--from X,Y [--plot FILE.png]]",
      words, {"--rooms"});
  ValidateArgs v;
  v.usage = args.tool_usage();
  v.world_file = args.Required("--world");
  v.map_file = args.String("--map", "");
  v.profile_name = args.String("--profile", "nava");
  v.table_file = args.String("--table", "");
  const std::string predict = args.String("--predict", "");
  v.time = args.Double("--time", 0.0, -1e9, 1e9);
  ValidationOptions& options = v.validation;
  options.links = static_cast<int>(args.Int("--links", 300, 1, 100000));
  options.packets = static_cast<int>(args.Int("--packets", 4, 1, 1000));
  options.seed = static_cast<std::uint32_t>(args.Int("--seed", 1, 0, 4294967295L));
  options.threads = static_cast<int>(args.Int("--threads", 2, 1, 64));
  v.out = args.String("--out", ".");
  v.rir_dir = args.String("--rir-dir", "");
  v.static_pairs = static_cast<int>(args.Int("--static-pairs", 0, 0, 100000));
  v.fate.pairs = std::max(1, v.static_pairs);
  v.fate.packets = static_cast<int>(args.Int("--pair-packets", 30, 1, 10000));
  v.fate.fate_distance = args.Double("--fate-distance", v.fate.fate_distance, 0.001, 100.0);
  v.fate.seed = options.seed;
  v.rooms = args.Switch("--rooms");
  const std::string from = args.String("--from", "");
  if (!from.empty()) {
    if (!v.rooms) args.Fail("--from: expected with --rooms");
    v.rooms_from = ParsePoint(args, from);
  }
  v.rooms_plot = args.String("--plot", "");
  if (!v.rooms_plot.empty() && !v.rooms_from) args.Fail("--plot: expected with --rooms --from X,Y");
  if (v.rooms && (!predict.empty() || v.static_pairs > 0)) {
    args.Fail("--rooms: expected without --predict and --static-pairs");
  }
  if (!v.rir_dir.empty() && (v.rooms || !predict.empty() || v.static_pairs > 0)) {
    args.Fail("--rir-dir: the rooms the validation renders; expected without --rooms, --predict and --static-pairs");
  }
  if (predict.empty()) args.CheckAllUsed();
  options.profile = Profile(args, v.profile_name);
  v.fate.profile = options.profile;
  if (!predict.empty() && v.static_pairs > 0) args.Fail("--predict and --static-pairs: expected one of them");
  if (predict.empty()) return v;
  // "--predict X1,Y1 X2,Y2": the second point is the next argument (or the same one, quoted).
  v.predict = true;
  std::string a = predict, b;
  const auto space = predict.find(' ');
  if (space != std::string::npos) {
    a = predict.substr(0, space);
    const auto second = predict.find_first_not_of(' ', space);
    if (second == std::string::npos) args.Fail("--predict: expected two points X1,Y1 X2,Y2");
    b = predict.substr(second);
    if (!args.positional().empty()) args.Fail("unexpected argument " + args.positional().front());
  } else {
    if (args.positional().size() != 1) args.Fail("--predict: expected two points X1,Y1 X2,Y2");
    b = args.positional().front();
  }
  args.CheckAllUsed();
  v.from = ParsePoint(args, a);
  v.to = ParsePoint(args, b);
  return v;
}

}  // namespace audio_propagation::tools

namespace audio_propagation::tools {

RangingBenchArgs ParseRangingBenchArgs(const std::vector<std::string>& words) {
  const ToolArgs args("ranging_bench",
                      "ranging_bench [--worlds W1.yaml,W2.yaml] [--teams 2,5,10,20] [--scenes 2] [--rounds 2] "
                      "[--profile room|nava] [--rate 48000] [--seed 1] [--threads 2] [--plot FILE.png] "
                      "[--rir-dir DIR[,DIR...]]",
                      words);
  RangingBenchArgs r;
  r.usage = args.tool_usage();
  r.rir_dir = args.String("--rir-dir", "");
  const auto split = [](const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string item; std::getline(in, item, ',');) out.push_back(item);
    return out;
  };
  r.worlds = split(args.String("--worlds", package_data::DataFile("maps/office_team20_world.yaml") + "," +
                                               package_data::DataFile("maps/campus_team60_world.yaml")));
  for (const std::string& w : r.worlds) {
    if (w.empty()) args.Fail("--worlds: expected world files separated by commas, got an empty name");
  }
  const std::string teams = args.String("--teams", "");
  if (!teams.empty()) {
    r.teams.clear();
    for (const std::string& t : split(teams)) {
      char* end = nullptr;
      const long n = std::strtol(t.c_str(), &end, 10);
      if (t.empty() || *end || n < 2 || n > 100) args.Fail("--teams: expected robot counts from 2 to 100 separated by commas, got " + teams);
      r.teams.push_back(static_cast<int>(n));
    }
  }
  r.scenes = static_cast<int>(args.Int("--scenes", r.scenes, 1, 1000));
  r.rounds = static_cast<int>(args.Int("--rounds", r.rounds, 1, 100));
  r.profile = Profile(args, args.String("--profile", "room"));
  r.rate = args.Double("--rate", r.rate, nava_modem::kMinSampleRate, nava_modem::kMaxSampleRate);
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.threads = static_cast<int>(args.Int("--threads", r.threads, 1, 64));
  r.plot = args.String("--plot", "");
  args.CheckAllUsed();
  return r;
}

}  // namespace audio_propagation::tools
