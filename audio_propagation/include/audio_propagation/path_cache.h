#pragma once

#include <cstdint>
#include <list>
#include <optional>
#include <unordered_map>
#include <utility>

#include "audio_propagation/propagation_model.h"

namespace audio_propagation {

// A bounded least-recently-used cache of sound paths keyed on the cells of the source and the
// listener, so robots that stand still (or nearly) do not pay for the same path every step.
// (Stage's cache was unbounded.) A cached path is the one computed for some position in the
// same pair of cells, so it is exact to within a cell. Counts hits, misses and evictions.
// Cells outside 0..65535 (a robot off the map, or with no pose yet) are never cached.
class PathCache {
 public:
  explicit PathCache(std::size_t capacity) : capacity_(capacity) {}

  std::optional<SoundPath> Find(const Eigen::Vector2i& source_cell, const Eigen::Vector2i& listener_cell);
  void Insert(const Eigen::Vector2i& source_cell, const Eigen::Vector2i& listener_cell, SoundPath path);

  std::size_t size() const { return index_.size(); }
  std::size_t capacity() const { return capacity_; }
  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }
  std::uint64_t evictions() const { return evictions_; }

 private:
  using Key = std::uint64_t;
  static bool Keyable(const Eigen::Vector2i& s, const Eigen::Vector2i& r);
  static Key MakeKey(const Eigen::Vector2i& s, const Eigen::Vector2i& r);

  std::size_t capacity_;
  std::list<std::pair<Key, SoundPath>> order_;  // most recent first
  std::unordered_map<Key, std::list<std::pair<Key, SoundPath>>::iterator> index_;
  std::uint64_t hits_ = 0, misses_ = 0, evictions_ = 0;
};

}  // namespace audio_propagation
