#include "sounds_good_explorer/heard_messages.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "grid/option_checks.h"

namespace sounds_good_explorer {

using grid::RequireAbove;

void ValidateOptions(const AudioTermOptions& o) {
  RequireAbove("audio lifetime (s)", o.lifetime, 0.0);
  if (!(o.level_full_db > o.level_floor_db))
    throw std::invalid_argument("audio level_full_db (" + std::to_string(o.level_full_db) +
                                ") must be above level_floor_db (" +
                                std::to_string(o.level_floor_db) + ")");
  if (o.capacity == 0) throw std::invalid_argument("audio capacity must be at least 1 message");
}

HeardMessages::HeardMessages(const AudioTermOptions& options) : options_(options) {
  ValidateOptions(options_);
}

void HeardMessages::Add(std::uint32_t marker, double direction, double robot_yaw,
                        double level_db, double time, ListenMode mode) {
  if (mode == ListenMode::kNone) return;
  if (mode == ListenMode::kBidirectional && !std::isnan(direction))
    direction = std::cos(direction) >= 0.0 ? 0.0 : M_PI;
  if (messages_.size() >= options_.capacity) {
    messages_.pop_front();
    ++dropped_;
  }
  messages_.push_back({marker, direction + robot_yaw, level_db, time,
                       mode == ListenMode::kBidirectional});
}

void HeardMessages::Forget(double time) {
  while (!messages_.empty() && time - messages_.front().time >= options_.lifetime)
    messages_.pop_front();
}

double HeardMessages::Score(std::uint32_t marker, double cell_direction, double time) const {
  double score = 0.0;
  for (const HeardMessage& m : messages_) {
    if (m.marker != marker || std::isnan(m.direction)) continue;
    const double freshness = 1.0 - (time - m.time) / options_.lifetime;
    if (freshness <= 0.0) continue;
    const double loudness = std::clamp((m.level_db - options_.level_floor_db) /
                                           (options_.level_full_db - options_.level_floor_db),
                                       0.0, 1.0);
    const double agreement = std::cos(m.direction - cell_direction);
    // One bit says only which half-plane: every direction in it agrees alike.
    const double weight = m.half_plane ? (agreement >= 0.0 ? 1.0 : -1.0) : agreement;
    score += weight * std::min(freshness, 1.0) * loudness;
  }
  return score;
}

bool HeardMessages::Has(std::uint32_t marker) const {
  return std::any_of(messages_.begin(), messages_.end(),
                     [marker](const HeardMessage& m) { return m.marker == marker; });
}

}  // namespace sounds_good_explorer
