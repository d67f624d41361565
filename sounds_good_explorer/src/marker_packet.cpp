#include "sounds_good_explorer/marker_packet.h"

#include <stdexcept>
#include <string>

namespace sounds_good_explorer {

std::array<std::uint8_t, 4> EncodeMarkerPacket(std::uint32_t marker) {
  if (marker > kMaxMarkerId)
    throw std::invalid_argument("marker id " + std::to_string(marker) +
                                " does not fit an announcement (at most " +
                                std::to_string(kMaxMarkerId) + ")");
  return {'S', 'G', static_cast<std::uint8_t>(marker >> 8), static_cast<std::uint8_t>(marker)};
}

std::optional<std::uint32_t> DecodeMarkerPacket(const std::vector<std::uint8_t>& data) {
  if (data.size() != 4 || data[0] != 'S' || data[1] != 'G') return std::nullopt;
  return (static_cast<std::uint32_t>(data[2]) << 8) | data[3];
}

}  // namespace sounds_good_explorer
