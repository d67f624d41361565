#include "world_sim/world_config.h"

namespace world_sim {

std::optional<Microphone> ParseMicrophone(const std::string& name) {
  if (name == "omni") return Microphone::kOmni;
  if (name == "bidirectional") return Microphone::kBidirectional;
  if (name == "none") return Microphone::kNone;
  return std::nullopt;
}

const char* MicrophoneName(Microphone m) {
  switch (m) {
    case Microphone::kOmni:
      return "omni";
    case Microphone::kBidirectional:
      return "bidirectional";
    case Microphone::kNone:
      return "none";
  }
  return "?";
}

}  // namespace world_sim
