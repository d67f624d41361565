#pragma once

// decode_table_bench's command line, parsed apart from the tool so that tests and the fuzzer can
// call it.
//
//   decode_table_bench --profile nava|room [--out FILE] [--packets 12] [--quick] [--threads 2]
//                      [--seed 1] [--dir DIR] [--snr-db LIST] [--rt60 LIST]
//                      [--response statistical|measured-like|measured [--rir-dir DIR[,DIR...]]]
//   decode_table_bench --profile nava|room --calibrate --rir-dir DIR[,DIR...] [--noise-file FILE.wav]
//                      [--table FILE] [--packets 10] [--snr-db LIST] [--threads 2] [--seed 1] [--dir DIR]
//   decode_table_bench --profile nava --whine-harm [--table FILE] [--out FILE] [--packets 16] [--quick]
//                      [--threads 2] [--seed 1]
#include <string>
#include <vector>

#include "nava_modem/modem_profile.h"
#include "nava_modem/room_channel.h"
#include "tool_args/tool_args.h"

namespace audio_propagation::tools {

struct DecodeTableRequest {
  nava_modem::Profile profile = nava_modem::Profile::kNava;
  bool quick = false;
  int packets = 12, threads = 2;
  unsigned seed = 1;
  std::string out, dir;
  std::vector<double> snr_db;  // --snr-db; empty: the default axis
  std::vector<double> rt60;    // --rt60; empty: the profile's default axis
  // --response statistical|measured-like|measured: the rooms the table's packets are heard
  // through; measured: the rooms of --rir-dir (folders, comma-separated) moved to each cell's
  // RT60 and DRR (moved_rooms.h).
  nava_modem::RoomOptions::Model model = nava_modem::RoomOptions::Model::kStatistical;
  // --calibrate: the model held against the real receiver through measured rooms
  // (model_calibration.h) instead of a table measured.
  bool calibrate = false;
  // --whine-harm: a table (--table, else the shipped one) written to --out with its whine harm
  // curve measured anew (whine_harm.h); nava only.
  bool whine_harm = false;
  std::string rir_dir, noise_file, table_file;
  std::string command;         // how the table was made: the whole command line
  multirobot_audio::tools::ToolUsage usage;  // to refuse what turns out wrong while running
};

// Throws multirobot_audio::tools::UsageError naming what it refuses, HelpRequested for -h.
DecodeTableRequest ParseDecodeTableBenchArgs(const std::vector<std::string>& words);

}  // namespace audio_propagation::tools
