#pragma once

#include <cstdint>
#include <deque>
#include <optional>

namespace nava_modem {

// The quiet level a robot hears where it is now, for its carrier threshold. The thesis's MAC
// listens once, at start-up, and keeps the loudest level of that silence: a robot that then
// drives from a quiet room into one with a fan hears the fan as a carrier for ever and never
// sends. This keeps the thesis's statistic (the loudest level of silence) over blocks of a
// fixed length and reports the quietest block of the last few, so a steady noise sets it, a
// passing one (a packet, a door) does not unless it fills every block of the window, and a
// new room is followed within the window's length.
class NoiseFloor {
 public:
  // Blocks of `block_ticks` heard ticks; the floor is read over the last `blocks` whole ones.
  // Throws std::invalid_argument unless both are at least 1.
  NoiseFloor(int block_ticks, int blocks);

  // Hears `ticks` ticks at `level_db`; true if one or more blocks ended (the floor may have moved).
  bool Hear(double level_db, std::uint64_t ticks = 1);

  // The quietest of the last whole blocks' loudest levels; none before a block has ended.
  std::optional<double> floor_db() const;
  // Heard ticks until the current block ends (at least 1).
  std::uint64_t TicksToBlockEnd() const { return static_cast<std::uint64_t>(block_ticks_) - in_block_; }

 private:
  int block_ticks_;
  std::size_t blocks_;
  std::uint64_t in_block_ = 0;   // ticks heard in the current block
  double block_loudest_ = 0.0;   // its loudest level (valid once in_block_ > 0)
  std::deque<double> loudest_;   // the whole blocks' loudest levels, newest last
};

}  // namespace nava_modem
