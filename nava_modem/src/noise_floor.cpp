#include "nava_modem/noise_floor.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace nava_modem {

NoiseFloor::NoiseFloor(int block_ticks, int blocks) : block_ticks_(block_ticks), blocks_(blocks > 0 ? blocks : 0) {
  if (block_ticks < 1 || blocks < 1) {
    throw std::invalid_argument("noise floor: blocks of " + std::to_string(block_ticks) + " ticks, " +
                                std::to_string(blocks) + " of them; both must be at least 1");
  }
}

bool NoiseFloor::Hear(double level_db, std::uint64_t ticks) {
  bool ended = false;
  while (ticks > 0) {
    const std::uint64_t take = std::min(ticks, TicksToBlockEnd());
    block_loudest_ = in_block_ == 0 ? level_db : std::max(block_loudest_, level_db);
    in_block_ += take;
    ticks -= take;
    if (in_block_ == static_cast<std::uint64_t>(block_ticks_)) {
      loudest_.push_back(block_loudest_);
      if (loudest_.size() > blocks_) loudest_.pop_front();
      in_block_ = 0;
      ended = true;
    }
  }
  return ended;
}

std::optional<double> NoiseFloor::floor_db() const {
  if (loudest_.empty()) return std::nullopt;
  return *std::min_element(loudest_.begin(), loudest_.end());
}

}  // namespace nava_modem
