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
  int speed = 0;  // the profile's rate step (--speed; --rate is the sample rate)
  bool list_rates = false;  // --list-rates: print the profile's rates instead
  std::vector<std::vector<std::uint8_t>> packets;  // each a frame's data bytes (4 on nava, 1 to 255 on room)
};

// Throws multirobot_audio::tools::UsageError naming what it refuses, HelpRequested for -h.
NavaEncodeOptions ParseNavaEncodeArgs(const std::vector<std::string>& words);

}  // namespace nava_modem::tools
