#include "decode_table_bench_args.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace audio_propagation::tools {
namespace {

using multirobot_audio::tools::ToolArgs;

// A comma-separated list of ascending numbers from -60 to 60 (dB).
std::vector<double> AxisArg(const ToolArgs& args, const std::string& flag, const std::string& list) {
  std::vector<double> axis;
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    const std::string item = list.substr(at, comma - at);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end || !std::isfinite(v) || std::fabs(v) > 60.0 || (!axis.empty() && v <= axis.back())) {
      args.Fail(flag + ": expected ascending numbers from -60 to 60 separated by commas, got " + list);
    }
    axis.push_back(v);
    at = comma + 1;
  }
  return axis;
}

}  // namespace

DecodeTableRequest ParseDecodeTableBenchArgs(const std::vector<std::string>& words) {
  const ToolArgs args("decode_table_bench",
                      "decode_table_bench --profile nava|room [--out FILE] [--packets 12] [--quick] [--threads 2] [--seed 1] "
                      "[--dir DIR] [--snr-db LIST] | --profile nava|room --calibrate --rir-dir DIR [--noise-file FILE.wav] "
                      "[--table FILE] [--packets 10] [--snr-db LIST] [--threads 2] [--seed 1] [--dir DIR]",
                      words, {"--quick", "--calibrate"});
  DecodeTableRequest r;
  r.usage = args.tool_usage();
  const std::string name = args.Required("--profile");
  const auto profile = nava_modem::ParseProfile(name);
  if (!profile) args.Fail(std::string("--profile: expected ") + nava_modem::kProfileNames + ", got " + name);
  r.profile = *profile;
  r.quick = args.Switch("--quick");
  r.calibrate = args.Switch("--calibrate");
  r.packets = static_cast<int>(args.Int("--packets", r.quick ? 4 : r.calibrate ? 10 : 12, 1, 100000));
  r.threads = static_cast<int>(args.Int("--threads", 2, 1, 256));
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.out = args.String("--out", std::string("decode_table_") + nava_modem::ProfileName(r.profile) + ".yaml");
  r.dir = args.String("--dir", "");
  const std::string snr_list = args.String("--snr-db", "");
  r.rir_dir = args.String("--rir-dir", "");
  r.noise_file = args.String("--noise-file", "");
  r.table_file = args.String("--table", "");
  args.CheckAllUsed();
  if (r.calibrate) {
    if (r.rir_dir.empty()) args.Fail("--calibrate: expected --rir-dir DIR, the measured responses");
    if (r.quick || !args.String("--out", "").empty()) args.Fail("--calibrate measures no table: drop --quick and --out");
  } else if (!r.rir_dir.empty() || !r.noise_file.empty() || !r.table_file.empty()) {
    args.Fail("--rir-dir, --noise-file and --table go with --calibrate");
  }
  if (!snr_list.empty()) r.snr_db = AxisArg(args, "--snr-db", snr_list);
  r.command = "decode_table_bench";
  for (const std::string& word : words) r.command += " " + word;
  return r;
}

}  // namespace audio_propagation::tools
