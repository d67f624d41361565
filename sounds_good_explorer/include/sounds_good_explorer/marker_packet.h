#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace sounds_good_explorer {

// An announcement "I saw marker N": 4 bytes, 'S' 'G' and the id high byte first. The two tag
// bytes keep it apart from other packets on the same link (a local mutex packet's second byte
// is 'R' or 'L').
constexpr std::uint32_t kMaxMarkerId = 0xFFFF;

// Throws std::invalid_argument for an id above kMaxMarkerId.
std::array<std::uint8_t, 4> EncodeMarkerPacket(std::uint32_t marker);
// The marker id, or nullopt for anything that is not an announcement.
std::optional<std::uint32_t> DecodeMarkerPacket(const std::vector<std::uint8_t>& data);

}  // namespace sounds_good_explorer
