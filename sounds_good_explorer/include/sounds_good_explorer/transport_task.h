#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace sounds_good_explorer {

struct TaskOptions {
  std::uint32_t source = 1;     // marker id of the source (sought first)
  std::uint32_t sink = 2;       // marker id of the sink
  double work_time = 30.0;      // s of loading or unloading at a marker
  double arrive_radius = 0.6;   // m: this close to the marker the robot starts working
  double marker_memory = 5.0;   // s a sighting still guides the robot after the marker is lost
  double announce_window = 10.0;  // s: markers seen this recently are announced
  double announce_period = 2.0;   // s between announcements of one marker
};

void ValidateOptions(const TaskOptions& options);

// A completed job: finding a marker and working there for work_time (thesis section 3.1).
struct Job {
  int count = 0;            // this robot's jobs so far, including this one
  std::uint32_t marker = 0;
  double time = 0.0;        // s, when the work finished
};

// The transport task of thesis section 3.3: seek the source, work there, seek the sink, work
// there, and so on, announcing every marker seen in the last announce_window seconds. Positions
// are in the odom frame; the task knows nothing of maps or motion.
class TransportTask {
 public:
  explicit TransportTask(const TaskOptions& options);

  // A marker seen at `position` at `time`.
  void Seen(std::uint32_t marker, const Eigen::Vector2d& position, double time);
  // Where the sought marker was last seen, if within marker_memory.
  std::optional<Eigen::Vector2d> SoughtPosition(double time) const;
  // Given the robot's position, starts working when it is within arrive_radius of a fresh
  // sighting of the sought marker; finishes the work (and returns the job) after work_time.
  std::optional<Job> Update(const Eigen::Vector2d& robot, double time);
  // Markers due for announcement at `time` (seen in the window, not announced for a period).
  std::vector<std::uint32_t> DueAnnouncements(double time);

  std::uint32_t sought() const { return sought_; }
  bool working() const { return working_; }
  double work_started() const { return work_started_; }
  int jobs() const { return jobs_; }

 private:
  struct Sighting {
    Eigen::Vector2d position;
    double time = 0.0;
    double announced = -1e9;
  };
  TaskOptions options_;
  std::map<std::uint32_t, Sighting> seen_;
  std::uint32_t sought_;
  bool working_ = false;
  double work_started_ = 0.0;
  int jobs_ = 0;
};

}  // namespace sounds_good_explorer
