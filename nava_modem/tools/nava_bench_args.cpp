#include "nava_bench_args.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace nava_modem::tools {
namespace {

using multirobot_audio::tools::ToolArgs;

WhiteNoiseRequest ParseWhiteNoise(const ToolArgs& args) {
  WhiteNoiseRequest r;
  r.packets = static_cast<int>(args.Int("--packets", 60, 1, 100000));
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.snr_min = static_cast<int>(args.Int("--snr-min", -12, -60, 60));
  r.snr_max = static_cast<int>(args.Int("--snr-max", 0, -60, 60));
  r.dir = args.String("--dir", "");
  const std::string minimodem = args.String("--minimodem", "minimodem");
  r.modem = ProfileArgs(args);
  if (minimodem != "none" && r.modem.profile == Profile::kNava) r.minimodem = minimodem;
  args.CheckAllUsed();
  if (r.snr_min > r.snr_max) args.Fail("--snr-min must not be above --snr-max");
  return r;
}

RoomsRequest ParseRooms(const ToolArgs& args) {
  RoomsRequest r;
  r.packets = static_cast<int>(args.Int("--packets", 60, 1, 100000));
  r.plot_packets = static_cast<int>(args.Int("--plot-packets", 30, 0, 100000));
  r.rooms_per_row = static_cast<int>(args.Int("--rooms-per-row", 6, 1, 1000));
  // --plot-packets 0 draws no plot, so it does not bound the rooms.
  if (r.rooms_per_row > r.packets || (r.plot_packets > 0 && r.rooms_per_row > r.plot_packets)) {
    args.Fail("--rooms-per-row: expected at most the packets per row and per plot point");
  }
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.dir = args.String("--dir", "");
  const std::string which = args.String("--profile", "both");
  const std::string minimodem = args.String("--minimodem", "minimodem");
  r.plot = args.String("--plot", "");
  r.rir_dir = args.String("--rir-dir", "");
  r.rir_packets = static_cast<int>(args.Int("--rir-packets", 20, 1, 100000));
  r.measured_only = args.Switch("--measured-only");
  r.drier = args.AscendingList("--drier", -20.0, 40.0, "DRRs from -20 to 40 (dB)");
  const std::vector<double> curve_rt60 = args.AscendingList("--curve-rt60", 0.05, 10.0, "reverberation times from 0.05 to 10 (s)");
  if (!curve_rt60.empty()) r.curve_rt60 = curve_rt60;
  r.curve_drr_min = args.Double("--curve-drr-min", r.curve_drr_min, -39.0, 12.0);
  r.curve_snr_db = args.Double("--curve-snr", r.curve_snr_db, -60.0, 100.0);
  r.curve_model = RoomModelArg(args, r.curve_model);
  r.options = ModemArgs(args);
  if (r.curve_model == RoomOptions::Model::kMeasuredLike && r.options.sample_rate <= 10800.0) {
    args.Fail("--response measured-like: expected --rate above 10800 Hz (its responses reach 5400 Hz), got " +
              std::to_string(r.options.sample_rate));
  }
  args.CheckAllUsed();
  if (r.measured_only || r.plot_packets == 0) {
    for (const char* flag : {"--curve-rt60", "--curve-drr-min", "--curve-snr", "--response"}) {
      if (args.Switch(flag)) args.Fail(std::string(flag) + ": there is no delivery curve with --measured-only or --plot-packets 0");
    }
  }
  if (r.rir_dir.empty()) {
    for (const char* flag : {"--rir-packets", "--measured-only", "--drier"}) {
      if (args.Switch(flag)) {  // given at all
        args.Fail(std::string(flag) + ": there are no measured rooms; add --rir-dir DIR");
      }
    }
  }
  if (which == "both") {
    r.profiles = {Profile::kNava, Profile::kRoom};
  } else if (const auto p = ParseProfile(which)) {
    r.profiles = {*p};
  } else {
    args.Fail(std::string("--profile: expected both, ") + kProfileNames + ", got " + which);
  }
  if (minimodem != "none") r.minimodem = minimodem;
  return r;
}

DoaRequest ParseDoa(const ToolArgs& args) {
  DoaRequest r;
  r.packets = static_cast<int>(args.Int("--packets", 100, 1, 100000));
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.dir = args.String("--dir", "");
  r.plot = args.String("--plot", "");
  r.options = ModemArgs(args);
  args.CheckAllUsed();
  return r;
}

ArrivalRequest ParseArrival(const ToolArgs& args) {
  ArrivalRequest r;
  r.rir_dir = args.String("--rir-dir", "");
  r.packets = static_cast<int>(args.Int("--packets", 10, 1, 100000));
  r.snr_db = args.Double("--snr", 10.0, -60.0, 100.0);
  r.min_drr_db = args.Double("--min-drr", -8.0, -60.0, 60.0);
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.errors_out = args.String("--errors-out", "");
  const ToolModem modem = ProfileArgs(args);
  r.profile = args.Switch("--profile") ? modem.profile : Profile::kRoom;
  r.options = modem.options;
  args.CheckAllUsed();
  if (r.rir_dir.empty()) args.Fail("--arrival: expected --rir-dir DIR, a folder of measured impulse responses");
  return r;
}

LikenessRequest ParseLikeness(const ToolArgs& args) {
  LikenessRequest r;
  r.rir_dir = args.String("--rir-dir", "");
  r.rooms = static_cast<int>(args.Int("--like-rooms", r.rooms, 1, 1000));
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  // (The renderer's rooms need the band, up to 5400 Hz, under Nyquist: 11025 Hz is the lowest
  // card rate that holds it.)
  r.sample_rate = args.Double("--rate", r.sample_rate, 11025.0, 384000.0);
  args.CheckAllUsed();
  if (r.rir_dir.empty()) args.Fail("--likeness: expected --rir-dir DIR, a folder of measured impulse responses");
  return r;
}

SpliceRequest ParseSplice(const ToolArgs& args) {
  SpliceRequest r;
  r.early = args.String("--early", "");
  r.late = args.String("--late", "");
  r.out_dir = args.String("--out", "");
  r.sample_rate = args.Double("--rate", r.sample_rate, 11025.0, 384000.0);
  r.at_ms = args.AscendingList("--at-ms", 0.1, 1000.0, "times after the direct sound, ms");
  args.CheckAllUsed();
  if (r.early.empty() || r.late.empty()) args.Fail("--splice: expected --early A.wav[:K] and --late B.wav[:K], two impulse responses");
  if (r.at_ms.empty()) args.Fail("--splice: expected --at-ms T[,T...], where to splice (ms after the direct sound)");
  if (r.out_dir.empty()) args.Fail("--splice: expected --out DIR for the spliced responses");
  return r;
}

LinkCostRequest ParseLinkCost(const ToolArgs& args) {
  LinkCostRequest r;
  r.seconds = args.Double("--seconds", 120.0, 10.0, 3600.0);
  r.period = args.Double("--period", 6.0, 3.0, 600.0);
  r.runs = static_cast<int>(args.Int("--runs", 3, 1, 100));
  const ToolModem modem = ProfileArgs(args);
  r.profile = args.Switch("--profile") ? modem.profile : Profile::kRoom;
  r.options = modem.options;
  args.CheckAllUsed();
  return r;
}

FramesRequest ParseFrames(const ToolArgs& args) {
  FramesRequest r;
  r.rir_dir = args.String("--rir-dir", "");
  r.noise_file = args.String("--noise-file", "");
  r.frames = static_cast<int>(args.Int("--count", r.frames, 1, 10000));
  r.snr_db = args.Double("--snr", r.snr_db, -30.0, 80.0);
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.threads = static_cast<int>(args.Int("--threads", r.threads, 1, 64));
  const ToolModem modem = ProfileArgs(args);
  r.profile = args.Switch("--profile") ? modem.profile : Profile::kRoom;
  r.options = modem.options;
  const FrameFormat format = ProfileFormat(r.profile);
  r.bytes = static_cast<int>(args.Int("--bytes", std::min<long>(64, static_cast<long>(format.max_bytes)),
                                      static_cast<long>(format.min_bytes), static_cast<long>(format.max_bytes)));
  const std::string speeds = args.String("--speed", "all");
  if (speeds != "all") {
    const long speed = args.Int("--speed", 0, 0, format.rates - 1);
    r.speeds.push_back(static_cast<int>(speed));
  }
  args.CheckAllUsed();
  if (r.rir_dir.empty()) args.Fail("--frames: expected --rir-dir DIR, a folder of measured impulse responses");
  return r;
}

DirectionRequest ParseDirection(const ToolArgs& args) {
  DirectionRequest r;
  r.packets = static_cast<int>(args.Int("--packets", r.packets, 1, 1000));
  r.min_decoded = static_cast<int>(args.Int("--min-decoded", r.min_decoded, 0, 100000));
  // At most 1000: each cell's packets take seeds of their own from a thousand (direction_table.cpp).
  r.max_packets = static_cast<int>(args.Int("--max-packets", std::max(r.max_packets, r.packets), r.packets, 1000));
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.snr_db = args.Double("--snr", r.snr_db, -30.0, 80.0);
  const std::vector<double> rt60 = args.AscendingList("--rt60", 0.05, 10.0, "reverberation times from 0.05 to 10 (s)");
  if (!rt60.empty()) r.rt60 = rt60;
  const std::vector<double> drr = args.AscendingList("--drr", -39.0, 30.0, "DRRs from -39 to 30 (dB)");
  if (!drr.empty()) r.drr_db = drr;
  r.binaural_dir = args.String("--binaural-dir", "");
  r.errors_out = args.String("--errors-out", "");
  r.threads = static_cast<int>(args.Int("--threads", r.threads, 1, 64));
  const ToolModem modem = ProfileArgs(args);
  r.profile = args.Switch("--profile") ? modem.profile : Profile::kRoom;
  r.options = modem.options;
  args.CheckAllUsed();
  // The measured-like responses reach 5400 Hz.
  if (r.options.sample_rate <= 10800.0) {
    args.Fail("--direction: expected --rate above 10800 Hz (the rendered rooms reach 5400 Hz), got " +
              std::to_string(r.options.sample_rate));
  }
  return r;
}

}  // namespace

NavaBenchOptions ParseNavaBenchArgs(const std::vector<std::string>& words) {
  const std::string usage = std::string(
      "nava_bench [--rooms [--rir-dir DIR [--rir-packets 20] [--measured-only] [--drier DB,...]] [--curve-rt60 0.3,0.6,1] [--curve-drr-min -15] [--curve-snr 40] [--response statistical|measured-like] | --doa | --arrival --rir-dir DIR [--snr 10] [--min-drr -8] [--errors-out FILE.yaml] (--profile room the default) | --likeness --rir-dir DIR [--like-rooms 5] | --splice --early A.wav[:K] --late B.wav[:K] --at-ms T,... --out DIR | --link-cost [--seconds 120] [--period 6] [--runs 3] | --frames --rir-dir DIR [--bytes 64] [--speed all|R] [--count 20] [--snr 10] [--noise-file FILE] [--threads 2] | --direction [--packets 40] [--min-decoded 10] [--max-packets 1000] [--snr 20] [--rt60 0.3,0.6,1,2] [--drr -15,-9,-3,3,9] [--binaural-dir DIR] [--errors-out FILE.yaml] [--threads 2] (--profile room the default)] [--packets 60] [--rooms-per-row 6] [--plot-packets 30] [--plot FILE.png] [--seed 1] [--snr-min -12] "
      "[--snr-max 0] [--dir DIR] [--minimodem minimodem|none] ") + kModemUsage + " (with --rooms, --profile both is the default)";
  const ToolArgs args("nava_bench", usage, words, {"--rooms", "--doa", "--arrival", "--likeness", "--splice", "--link-cost", "--frames", "--direction", "--measured-only"});
  NavaBenchOptions o;
  o.usage = args.tool_usage();
  if (args.Switch("--direction")) {
    o.mode = NavaBenchOptions::Mode::kDirection;
    o.direction = ParseDirection(args);
  } else if (args.Switch("--frames")) {
    o.mode = NavaBenchOptions::Mode::kFrames;
    o.frames = ParseFrames(args);
  } else if (args.Switch("--link-cost")) {
    o.mode = NavaBenchOptions::Mode::kLinkCost;
    o.link_cost = ParseLinkCost(args);
  } else if (args.Switch("--likeness")) {
    o.mode = NavaBenchOptions::Mode::kLikeness;
    o.likeness = ParseLikeness(args);
  } else if (args.Switch("--splice")) {
    o.mode = NavaBenchOptions::Mode::kSplice;
    o.splice = ParseSplice(args);
  } else if (args.Switch("--arrival")) {
    o.mode = NavaBenchOptions::Mode::kArrival;
    o.arrival = ParseArrival(args);
  } else if (args.Switch("--doa")) {
    o.mode = NavaBenchOptions::Mode::kDoa;
    o.doa = ParseDoa(args);
  } else if (args.Switch("--rooms")) {
    o.mode = NavaBenchOptions::Mode::kRooms;
    o.rooms = ParseRooms(args);
  } else {
    o.white = ParseWhiteNoise(args);
  }
  return o;
}

}  // namespace nava_modem::tools
