#pragma once

#include <optional>
#include <string>

namespace sounds_good_explorer {

// How the explorer uses what its microphone reports (thesis section 3.2):
//  - omni: the direction a message came from;
//  - bidirectional: one bit of it, the front or the back half-plane;
//  - none: ignores audio (the "no audio" baseline; the robot still announces).
enum class ListenMode { kOmni, kBidirectional, kNone };

std::optional<ListenMode> ParseListenMode(const std::string& name);
const char* ListenModeName(ListenMode mode);

}  // namespace sounds_good_explorer
