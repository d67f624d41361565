#include "sounds_good_explorer/listen_mode.h"

namespace sounds_good_explorer {

std::optional<ListenMode> ParseListenMode(const std::string& name) {
  if (name == "omni") return ListenMode::kOmni;
  if (name == "bidirectional") return ListenMode::kBidirectional;
  if (name == "none") return ListenMode::kNone;
  return std::nullopt;
}

const char* ListenModeName(ListenMode mode) {
  switch (mode) {
    case ListenMode::kOmni: return "omni";
    case ListenMode::kBidirectional: return "bidirectional";
    case ListenMode::kNone: return "none";
  }
  return "?";
}

}  // namespace sounds_good_explorer
