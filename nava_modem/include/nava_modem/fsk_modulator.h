#pragma once

#include <cstdint>
#include <vector>

#include "nava_modem/modem_options.h"

namespace nava_modem {

// Phase-continuous binary FSK: 1 is MARK, 0 is SPACE. Between bits of different value the
// frequency moves along a raised-cosine ramp, and each burst fades in and out over a few
// milliseconds, so no step in phase, frequency or amplitude makes the speaker click.
class FskModulator {
 public:
  explicit FskModulator(const ModemOptions& options);  // validates the options

  // The samples of one burst carrying `bits` (0 or 1 each), at the options' sample rate.
  std::vector<float> Modulate(const std::vector<std::uint8_t>& bits) const;
  // A whole Nava packet (break and frame) for 4 data bytes.
  std::vector<float> ModulatePacket(const std::vector<std::uint8_t>& data) const;

  const ModemOptions& options() const { return options_; }

 private:
  ModemOptions options_;
};

}  // namespace nava_modem
