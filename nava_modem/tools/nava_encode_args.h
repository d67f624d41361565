#pragma once

// nava_encode's command line (nava_encode.cpp), parsed apart from the tool so that tests and
// the fuzzer can call it.
#include <cstdint>
#include <string>
#include <vector>

#include "modem_args.h"

namespace nava_modem::tools {

struct NavaEncodeOptions {
  std::string out;
  double gap = 0.5;  // s of silence before, between and after the packets
  ToolModem modem;
  std::vector<std::vector<std::uint8_t>> packets;  // 4 data bytes each
};

// Throws multirobot_audio::tools::UsageError naming what it refuses, HelpRequested for -h.
NavaEncodeOptions ParseNavaEncodeArgs(const std::vector<std::string>& words);

}  // namespace nava_modem::tools
