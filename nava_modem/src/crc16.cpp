#include "nava_modem/crc16.h"

#include <boost/crc.hpp>

namespace nava_modem {

std::optional<CrcVariant> ParseCrcVariant(const std::string& name) {
  if (name == "ccitt-false") return CrcVariant::kCcittFalse;
  if (name == "xmodem") return CrcVariant::kXmodem;
  return std::nullopt;
}

const char* CrcVariantName(CrcVariant variant) {
  return variant == CrcVariant::kXmodem ? "xmodem" : "ccitt-false";
}

std::uint16_t Crc16(CrcVariant variant, const std::uint8_t* data, std::size_t size) {
  if (variant == CrcVariant::kXmodem) {
    boost::crc_optimal<16, 0x1021, 0x0000, 0, false, false> crc;
    crc.process_bytes(data, size);
    return crc.checksum();
  }
  boost::crc_ccitt_type crc;  // poly 0x1021, init 0xFFFF, not reflected, no final xor
  crc.process_bytes(data, size);
  return crc.checksum();
}

}  // namespace nava_modem
