#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace nava_modem {

// The 16-bit CRCs a Nava link can be configured with. Both use the CCITT polynomial 0x1021,
// unreflected, with no final xor; they differ in the initial value.
enum class CrcVariant {
  kCcittFalse,  // init 0xFFFF: the thesis's "standard CCITT" (the default)
  kXmodem,      // init 0x0000
};

std::optional<CrcVariant> ParseCrcVariant(const std::string& name);  // ccitt-false | xmodem
const char* CrcVariantName(CrcVariant variant);

std::uint16_t Crc16(CrcVariant variant, const std::uint8_t* data, std::size_t size);
inline std::uint16_t Crc16(CrcVariant variant, const std::vector<std::uint8_t>& data) {
  return Crc16(variant, data.data(), data.size());
}

}  // namespace nava_modem
