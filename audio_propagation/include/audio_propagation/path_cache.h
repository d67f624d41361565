#pragma once

#include <cstdint>
#include <optional>

#include "audio_propagation/lru_cache.h"
#include "audio_propagation/propagation_model.h"

namespace audio_propagation {

// A bounded least-recently-used cache of sound paths keyed on the cells of the source and the
// listener, so robots that stand still (or nearly) do not pay for the same path every step.
// (Stage's cache was unbounded.) A cached path is the one computed for some position in the
// same pair of cells, so it is exact to within a cell. Counts hits, misses and evictions.
// Cells outside 0..65535 (a robot off the map, or with no pose yet) are never cached.
class PathCache {
 public:
  explicit PathCache(std::size_t capacity) : paths_(capacity) {}

  std::optional<SoundPath> Find(const Eigen::Vector2i& source_cell, const Eigen::Vector2i& listener_cell);
  void Insert(const Eigen::Vector2i& source_cell, const Eigen::Vector2i& listener_cell, SoundPath path);

  std::size_t size() const { return paths_.size(); }
  std::size_t capacity() const { return paths_.capacity(); }
  std::uint64_t hits() const { return paths_.hits(); }
  std::uint64_t misses() const { return paths_.misses(); }
  std::uint64_t evictions() const { return paths_.evictions(); }

 private:
  LruCache<std::uint64_t, SoundPath> paths_;
};

// A cell's key for the caches: 16 bits per coordinate (maps up to 65536 cells a side); none for a
// cell outside 0..65535.
std::optional<std::uint32_t> CellKey(const Eigen::Vector2i& cell);

}  // namespace audio_propagation
