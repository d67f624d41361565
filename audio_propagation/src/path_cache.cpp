#include "audio_propagation/path_cache.h"

namespace audio_propagation {

std::optional<std::uint32_t> CellKey(const Eigen::Vector2i& cell) {
  auto ok = [](int v) { return v >= 0 && v <= 0xFFFF; };
  if (!ok(cell.x()) || !ok(cell.y())) return std::nullopt;
  return (static_cast<std::uint32_t>(cell.x()) << 16) | static_cast<std::uint32_t>(cell.y());
}

namespace {

std::optional<std::uint64_t> PairKey(const Eigen::Vector2i& s, const Eigen::Vector2i& r) {
  const std::optional<std::uint32_t> a = CellKey(s), b = CellKey(r);
  if (!a || !b) return std::nullopt;
  return (static_cast<std::uint64_t>(*a) << 32) | *b;
}

}  // namespace

std::optional<SoundPath> PathCache::Find(const Eigen::Vector2i& source_cell, const Eigen::Vector2i& listener_cell) {
  const std::optional<std::uint64_t> key = PairKey(source_cell, listener_cell);
  if (!key) {
    paths_.CountMiss();
    return std::nullopt;
  }
  const SoundPath* path = paths_.Find(*key);
  if (!path) return std::nullopt;
  return *path;
}

void PathCache::Insert(const Eigen::Vector2i& source_cell, const Eigen::Vector2i& listener_cell, SoundPath path) {
  if (const std::optional<std::uint64_t> key = PairKey(source_cell, listener_cell)) paths_.Insert(*key, std::move(path));
}

}  // namespace audio_propagation
