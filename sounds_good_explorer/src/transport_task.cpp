#include "sounds_good_explorer/transport_task.h"

#include <stdexcept>
#include <string>

#include "grid/option_checks.h"

namespace sounds_good_explorer {

using grid::RequireAbove;
using grid::RequireAtLeast;

void ValidateOptions(const TaskOptions& o) {
  if (o.source == o.sink)
    throw std::invalid_argument("task source and sink must be different markers, both are " +
                                std::to_string(o.source));
  RequireAbove("task arrive_radius (m)", o.arrive_radius, 0.0);
  RequireAbove("task announce_period (s)", o.announce_period, 0.0);
  RequireAtLeast("task work_time (s)", o.work_time, 0.0);
  RequireAtLeast("task marker_memory (s)", o.marker_memory, 0.0);
  RequireAtLeast("task announce_window (s)", o.announce_window, 0.0);
}

TransportTask::TransportTask(const TaskOptions& options)
    : options_(options), sought_(options.source) {
  ValidateOptions(options_);
}

void TransportTask::Seen(std::uint32_t marker, const Eigen::Vector2d& position, double time) {
  Sighting& s = seen_[marker];
  s.position = position;
  s.time = time;
}

std::optional<Eigen::Vector2d> TransportTask::SoughtPosition(double time) const {
  const auto it = seen_.find(sought_);
  if (it == seen_.end() || time - it->second.time > options_.marker_memory) return std::nullopt;
  return it->second.position;
}

std::optional<Job> TransportTask::Update(const Eigen::Vector2d& robot, double time) {
  if (working_) {
    if (time - work_started_ < options_.work_time) return std::nullopt;
    working_ = false;
    ++jobs_;
    Job job{jobs_, sought_, time};
    sought_ = sought_ == options_.source ? options_.sink : options_.source;
    return job;
  }
  const std::optional<Eigen::Vector2d> target = SoughtPosition(time);
  if (target && (*target - robot).norm() <= options_.arrive_radius) {
    working_ = true;
    work_started_ = time;
  }
  return std::nullopt;
}

std::vector<std::uint32_t> TransportTask::DueAnnouncements(double time) {
  std::vector<std::uint32_t> due;
  for (auto& [marker, s] : seen_) {
    if (time - s.time > options_.announce_window) continue;
    if (time - s.announced < options_.announce_period) continue;
    s.announced = time;
    due.push_back(marker);
  }
  return due;
}

}  // namespace sounds_good_explorer
