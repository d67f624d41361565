#include "decode_table_bench_args.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "whine_harm.h"

namespace audio_propagation::tools {

using multirobot_audio::tools::ToolArgs;

DecodeTableRequest ParseDecodeTableBenchArgs(const std::vector<std::string>& words) {
  const ToolArgs args("decode_table_bench",
                      "decode_table_bench --profile nava|room [--out FILE] [--packets 12] [--quick] [--threads 2] [--seed 1] "
                      "[--dir DIR] [--snr-db LIST] [--rt60 LIST] [--response statistical|measured-like|measured [--rir-dir DIR[,DIR...]]] | --profile nava|room --calibrate --rir-dir DIR[,DIR...] [--noise-file FILE.wav] "
                      "[--table FILE] [--packets 10] [--snr-db LIST] [--threads 2] [--seed 1] [--dir DIR] | --profile nava "
                      "--whine-harm [--table FILE] [--out FILE] [--packets 16] [--quick] [--threads 2] [--seed 1]",
                      words, {"--quick", "--calibrate", "--whine-harm"});
  DecodeTableRequest r;
  r.usage = args.tool_usage();
  const std::string name = args.Required("--profile");
  const auto profile = nava_modem::ParseProfile(name);
  if (!profile) args.Fail(std::string("--profile: expected ") + nava_modem::kProfileNames + ", got " + name);
  r.profile = *profile;
  r.quick = args.Switch("--quick");
  r.calibrate = args.Switch("--calibrate");
  r.whine_harm = args.Switch("--whine-harm");
  r.packets = static_cast<int>(
      args.Int("--packets", r.quick ? 4 : r.calibrate ? 10 : r.whine_harm ? kWhineHarmPackets : 12, 1, 100000));
  r.threads = static_cast<int>(args.Int("--threads", 2, 1, 256));
  r.seed = static_cast<unsigned>(args.Int("--seed", 1, 0, 4294967295L));
  r.out = args.String("--out", std::string("decode_table_") + nava_modem::ProfileName(r.profile) + ".yaml");
  r.dir = args.String("--dir", "");
  const std::string snr_list = args.String("--snr-db", "");
  const std::string rt60_list = args.String("--rt60", "");
  const std::string response = args.String("--response", "statistical");
  const auto model = nava_modem::ParseRoomModel(response);
  if (!model) args.Fail("--response " + response + ": expected " + nava_modem::kRoomModelNames);
  r.model = *model;
  r.rir_dir = args.String("--rir-dir", "");
  r.noise_file = args.String("--noise-file", "");
  r.table_file = args.String("--table", "");
  args.CheckAllUsed();
  if (r.whine_harm) {
    if (r.calibrate) args.Fail("--whine-harm and --calibrate: one at a time");
    if (r.profile != nava_modem::Profile::kNava) args.Fail("--whine-harm: measured for nava's tones; expected --profile nava");
    if (!r.rir_dir.empty() || !r.noise_file.empty() || !snr_list.empty() || !rt60_list.empty() ||
        !args.String("--response", "").empty() || !r.dir.empty()) {
      args.Fail("--whine-harm keeps the table's cells and axes and makes no speech: drop --rir-dir, --noise-file, "
                "--snr-db, --rt60, --response and --dir");
    }
  } else if (r.calibrate) {
    if (r.rir_dir.empty()) args.Fail("--calibrate: expected --rir-dir DIR, the measured responses");
    if (r.quick || !args.String("--out", "").empty()) args.Fail("--calibrate measures no table: drop --quick and --out");
  } else if (r.model == nava_modem::RoomOptions::Model::kMeasured) {
    if (r.rir_dir.empty()) args.Fail("--response measured: expected --rir-dir DIR[,DIR...], the measured rooms to move");
    if (!r.noise_file.empty() || !r.table_file.empty()) args.Fail("--noise-file and --table go with --calibrate");
  } else if (!r.rir_dir.empty() || !r.noise_file.empty() || !r.table_file.empty()) {
    args.Fail("--rir-dir, --noise-file and --table go with --calibrate or --response measured (--table also with "
              "--whine-harm)");
  }
  if (!rt60_list.empty() && r.calibrate) args.Fail("--rt60 is a table's axis: it does not go with --calibrate");
  if (!args.String("--response", "").empty() && r.calibrate) {
    args.Fail("--response: the calibration's rooms are the measured ones of --rir-dir");
  }
  if (!snr_list.empty()) r.snr_db = args.AscendingList("--snr-db", -60.0, 60.0, "numbers from -60 to 60 (dB)");
  // The renderer's limit (RoomImpulseResponse): above 0, at most 10 s.
  if (!rt60_list.empty()) r.rt60 = args.AscendingList("--rt60", 1e-3, 10.0, "reverberation times from 0.001 to 10 (s)");
  r.command = "decode_table_bench";
  for (const std::string& word : words) r.command += " " + word;
  return r;
}

}  // namespace audio_propagation::tools
