#pragma once

// nava_decode's command line (nava_decode.cpp), parsed apart from the tool so that tests and
// the fuzzer can call it.
#include <optional>
#include <string>
#include <vector>

#include "modem_args.h"
#include "nava_modem/microphone2d.h"

namespace nava_modem::tools {

struct NavaDecodeOptions {
  double threshold_db = kToolCarrierThresholdDb;
  int max_fixed_bits = 2;
  std::string given_rate;  // --rate as given ("" when not): it must be the file's
  std::optional<std::vector<Microphone2D>> mics;  // --mics: the file is an array's recording
  // --diagnostics: where to write the nava receiver's trace of each break, as JSON ("" for none).
  std::string diagnostics;
  std::string file;
  ToolModem modem;  // the sample rate is --rate's (or 48000) until the file's is known
  multirobot_audio::tools::ToolUsage usage;  // to refuse a --rate the file contradicts
};

// Throws multirobot_audio::tools::UsageError naming what it refuses, HelpRequested for -h.
NavaDecodeOptions ParseNavaDecodeArgs(const std::vector<std::string>& words);

}  // namespace nava_modem::tools
