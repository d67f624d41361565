#pragma once

// nava_room's command line (nava_room.cpp), parsed apart from the tool so that tests and the
// fuzzer can call it.
#include <optional>
#include <string>
#include <vector>

#include "nava_modem/room_array.h"
#include "nava_modem/room_channel.h"
#include "tool_args/tool_args.h"

namespace nava_modem::tools {

struct NavaRoomOptions {
  std::string in, out;
  RoomOptions room;
  std::string noise;            // --noise as given ("white", "pink" or "")
  std::string interferer_path;  // "" for none
  std::string rir_path;         // --rir: a measured impulse response ("" for the statistical room)
  std::optional<int> rir_channel;  // --channel: which of its channels (none: it must have one)
  ArraySource source;           // no microphones: one channel, no array
  std::string mics;             // --mics as given
  multirobot_audio::tools::ToolUsage usage;  // to refuse options the input file contradicts
};

// Throws multirobot_audio::tools::UsageError naming what it refuses, HelpRequested for -h. The
// room options are checked against the input's sample rate only once it is read (NavaRoomFlag).
NavaRoomOptions ParseNavaRoomArgs(const std::vector<std::string>& words);

// The flag that sets a RoomOptions or ArraySource field (RoomOptionError::field()), to name it
// in errors.
const std::string& NavaRoomFlag(const std::string& field);

}  // namespace nava_modem::tools
