#include "audio_propagation/path_cache.h"

namespace audio_propagation {

bool PathCache::Keyable(const Eigen::Vector2i& s, const Eigen::Vector2i& r) {
  auto ok = [](int v) { return v >= 0 && v <= 0xFFFF; };
  return ok(s.x()) && ok(s.y()) && ok(r.x()) && ok(r.y());
}

PathCache::Key PathCache::MakeKey(const Eigen::Vector2i& s, const Eigen::Vector2i& r) {
  // 16 bits per coordinate: maps up to 65536 cells a side.
  auto u = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint16_t>(v)); };
  return (u(s.x()) << 48) | (u(s.y()) << 32) | (u(r.x()) << 16) | u(r.y());
}

std::optional<SoundPath> PathCache::Find(const Eigen::Vector2i& source_cell,
                                         const Eigen::Vector2i& listener_cell) {
  const auto it = Keyable(source_cell, listener_cell) ? index_.find(MakeKey(source_cell, listener_cell))
                                                      : index_.end();
  if (it == index_.end()) {
    ++misses_;
    return std::nullopt;
  }
  ++hits_;
  order_.splice(order_.begin(), order_, it->second);
  return it->second->second;
}

void PathCache::Insert(const Eigen::Vector2i& source_cell, const Eigen::Vector2i& listener_cell,
                       SoundPath path) {
  if (capacity_ == 0 || !Keyable(source_cell, listener_cell)) return;
  const Key key = MakeKey(source_cell, listener_cell);
  const auto it = index_.find(key);
  if (it != index_.end()) {
    it->second->second = std::move(path);
    order_.splice(order_.begin(), order_, it->second);
    return;
  }
  if (index_.size() >= capacity_) {
    index_.erase(order_.back().first);
    order_.pop_back();
    ++evictions_;
  }
  order_.emplace_front(key, std::move(path));
  index_[key] = order_.begin();
}

}  // namespace audio_propagation
