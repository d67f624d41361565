#include "nava_room_args.h"

#include <cmath>
#include <cstdlib>
#include <map>

#include "modem_args.h"
#include "nava_modem/direction_estimator.h"

namespace nava_modem::tools {
namespace {

using multirobot_audio::tools::ToolArgs;

// Any finite number; the ranges are RoomOptions' own (ValidateRoomOptions), so that the tool
// and the library cannot disagree.
double Number(const ToolArgs& args, const std::string& flag, double fallback) {
  const std::string v = args.String(flag, "");
  if (v.empty()) return fallback;
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (*end || !std::isfinite(x)) args.Fail(flag + " " + v + ": expected a number");
  return x;
}

}  // namespace

const std::string& NavaRoomFlag(const std::string& field) {
  static const std::map<std::string, std::string> flags = {
      {"rt60", "--rt60"},          {"drr_db", "--drr"},        {"tilt_db", "--tilt"},
      {"tilt_low_hz", "--tilt-band"}, {"tilt_high_hz", "--tilt-band"}, {"clock_offset", "--clock"},
      {"snr_db", "--snr"},         {"sir_db", "--sir"},        {"whine_hz", "--whine"},
      {"whine_sir_db", "--whine-sir"}, {"whine_am_hz", "--whine-am"}, {"sample_rate", "--in"},
      {"bearing", "--bearing"},    {"distance", "--distance"}, {"response", "--rir"},
      {"model", "--response"}};
  return flags.at(field);
}

NavaRoomOptions ParseNavaRoomArgs(const std::vector<std::string>& words) {
  const std::string usage =
      "nava_room --in CLEAN.wav --out ROOM.wav [--rt60 S --drr DB [--response statistical|measured-like] | --rir FILE.wav "
      "[--channel K]] [--tilt DB] [--tilt-band LO,HI] "
      "[--clock PERCENT] [--noise white|pink] [--snr DB] [--interferer FILE] [--sir DB] [--whine HZ] "
      "[--whine-sir DB] [--whine-am HZ] [--seed N] [--mics X1,Y1,X2,Y2,... [--bearing DEG] [--distance M]]";
  const ToolArgs args("nava_room", usage, words);
  NavaRoomOptions r;
  r.usage = args.tool_usage();
  r.in = args.Required("--in");
  r.out = args.Required("--out");
  RoomOptions& o = r.room;
  o.rt60 = Number(args, "--rt60", o.rt60);
  o.drr_db = Number(args, "--drr", o.drr_db);
  o.model = RoomModelArg(args, RoomOptions::Model::kStatistical);
  r.rir_path = args.String("--rir", "");
  if (!args.String("--channel", "").empty()) r.rir_channel = static_cast<int>(args.Int("--channel", 0, 0, 255));
  o.tilt_db = Number(args, "--tilt", o.tilt_db);
  const std::string band = args.String("--tilt-band", "");
  if (!band.empty()) {
    char* end = nullptr;
    o.tilt_low_hz = std::strtod(band.c_str(), &end);
    if (*end != ',') args.Fail("--tilt-band " + band + ": expected LO,HI in Hz, e.g. 2300,3700");
    const char* high = end + 1;
    o.tilt_high_hz = std::strtod(high, &end);
    if (*end || end == high) args.Fail("--tilt-band " + band + ": expected LO,HI in Hz, e.g. 2300,3700");
  }
  o.clock_offset = Number(args, "--clock", 0.0) / 100.0;
  r.noise = args.String("--noise", "");
  if (r.noise == "white") {
    o.noise = RoomOptions::Noise::kWhite;
  } else if (r.noise == "pink") {
    o.noise = RoomOptions::Noise::kPink;
  } else if (!r.noise.empty()) {
    args.Fail("--noise " + r.noise + ": expected white or pink");
  }
  r.interferer_path = args.String("--interferer", "");
  o.snr_db = Number(args, "--snr", o.snr_db);
  o.sir_db = Number(args, "--sir", o.sir_db);
  o.whine_hz = Number(args, "--whine", o.whine_hz);
  o.whine_sir_db = Number(args, "--whine-sir", o.whine_sir_db);
  o.whine_am_hz = Number(args, "--whine-am", o.whine_am_hz);
  o.seed = static_cast<std::uint32_t>(args.Int("--seed", 1, 0, 4294967295L));
  r.mics = args.String("--mics", "");
  ArraySource& source = r.source;
  source.bearing = Number(args, "--bearing", 0.0) * 3.141592653589793 / 180.0;
  source.distance = Number(args, "--distance", source.distance);
  args.CheckAllUsed();
  if (!r.mics.empty() && o.model != RoomOptions::Model::kStatistical) {
    args.Fail(std::string("--response ") + RoomModelName(o.model) + ": an array's microphones hear the statistical room (room_array.h); drop one of them");
  }
  if (!r.mics.empty()) {
    try {
      source.mics = ParseMicPositions(r.mics);
    } catch (const std::invalid_argument& e) {
      args.Fail(std::string("--mics: ") + e.what());
    }
    try {
      ValidateArraySource(source);
    } catch (const RoomOptionError& e) {
      args.Fail(e.field() == "mics" ? "--mics " + r.mics + ": " + e.what() : NavaRoomFlag(e.field()) + ": " + e.what());
    }
  }
  if (!r.rir_path.empty()) {
    // A measured response is the whole room: a statistical one beside it, or an array's
    // microphones that one response cannot serve, would be a mistake in the command.
    for (const char* flag : {"--rt60", "--drr", "--mics", "--response"}) {
      if (!args.String(flag, "").empty()) args.Fail(std::string(flag) + ": the room is the measured response of --rir; drop one of them");
    }
  } else if (r.rir_channel) {
    args.Fail("--channel: there is no response to take a channel of; add --rir FILE.wav");
  }
  for (const char* flag : {"--bearing", "--distance"}) {
    if (!args.String(flag, "").empty() && r.mics.empty()) {
      args.Fail(std::string(flag) + ": there is no microphone array to place the source around; add --mics X1,Y1,X2,Y2,...");
    }
  }
  // A ratio for a disturbance that is not there is a mistake in the command, not a no-op.
  if (!args.String("--snr", "").empty() && o.noise == RoomOptions::Noise::kNone) {
    args.Fail("--snr: there is no noise to set; add --noise white|pink");
  }
  if (!args.String("--sir", "").empty() && r.interferer_path.empty()) {
    args.Fail("--sir: there is no interferer to set; add --interferer FILE");
  }
  for (const char* flag : {"--whine-sir", "--whine-am"}) {
    if (!args.String(flag, "").empty() && o.whine_hz == 0.0) {
      args.Fail(std::string(flag) + ": there is no whine to set; add --whine HZ");
    }
  }
  return r;
}

}  // namespace nava_modem::tools
