#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "audio_propagation/corner_distances.h"
#include "audio_propagation/corner_shadows.h"
#include "audio_propagation/diffraction_points.h"
#include "audio_propagation/lru_cache.h"
#include "audio_propagation/visibility_graph.h"
#include "grid/occupancy_map.h"

namespace audio_propagation {

struct PropagationOptions {
  DiffractionRule rule = DiffractionRule::kMasks;
  double source_level_db = 70.0;    // level at the reference distance
  double reference_distance = 1.0;  // m (d0)
  double threshold_db = 40.0;       // quieter than this is not heard
  double max_range = 0.0;           // m of path length beyond which nothing is heard; 0 = no limit
  double speed_of_sound = 343.0;    // m/s
  int threads = 2;                  // for building the visibility graph
};

// Throws std::invalid_argument naming the option when it is impossible (negative range, a
// threshold above the source level, ...).
void ValidateOptions(const PropagationOptions& options);

// The shortest path sound takes from a source to a listener, and what arrives.
struct SoundPath {
  bool reachable = false;           // a path exists (within max_range)
  bool audible = false;             // and it arrives above the threshold
  double length = 0.0;              // m
  std::vector<Eigen::Vector2d> polyline;  // world points from source to listener
  int bends = 0;                    // diffraction points on the way
  double level_db = 0.0;            // L_source - 20 log10(max(d, d0) / d0)
  double arrival_angle = 0.0;       // world-frame direction the sound comes from (NaN at length 0)
  double travel_time = 0.0;         // s
};

// Which graph nodes a listener sees, remembered cell by cell (key: CellKey of the cell), for a caller
// that asks for paths to the same listeners again and again while they stay in their cells
// (AudioChannel: every packet's paths to every robot). What is kept is the set of nodes seen from
// the first point asked about in a cell; the distances to them are always the asking point's own,
// so, as with PathCache, a path is exact to within a cell.
using VisibilityMemo = LruCache<std::uint32_t, std::vector<std::int32_t>>;

// Sound propagation on a map (thesis chapter 2): shortest paths around walls through the
// diffraction points, the inverse-square level, direction of arrival and travel time.
class PropagationModel {
 public:
  // Finds the diffraction points and builds the visibility graph (the expensive, once-per-map
  // part). Throws std::invalid_argument on impossible options.
  PropagationModel(grid::OccupancyMap map, const PropagationOptions& options);

  // Paths from each position flagged in `sources` to every other position: result[s][r], with
  // an unreachable SoundPath where r == s or s is not a source. A direct line of sight
  // short-cuts the graph; otherwise the path joins the corners the source sees to the corners
  // the listener sees through the precomputed corner distances.
  std::vector<std::vector<SoundPath>> Compute(const std::vector<Eigen::Vector2d>& positions,
                                              const std::vector<bool>& sources) const;

  // The paths from one source to many listeners (a map of where a robot is heard), without the
  // n x n table Compute would build; with `memo`, what each point sees is remembered and reused
  // cell by cell (see VisibilityMemo).
  std::vector<SoundPath> From(const Eigen::Vector2d& source, const std::vector<Eigen::Vector2d>& listeners,
                              VisibilityMemo* memo = nullptr) const;

  // The path between two world points.
  SoundPath Path(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const;

  // Received level at a path length (m).
  double LevelAt(double length) const;
  // The longest path (m) that can still be heard: the threshold distance, capped by max_range.
  double HearingDistance() const { return hearing_distance_; }

  const grid::OccupancyMap& map() const { return map_; }
  const PropagationOptions& options() const { return options_; }
  const VisibilityGraph& graph() const { return *graph_; }
  const CornerShadows& shadows() const { return *shadows_; }
  const std::vector<Eigen::Vector2i>& diffraction_points() const { return points_; }

 private:
  struct Visible {
    std::int32_t node;
    double distance;  // cells
  };
  // Graph nodes in line of sight of a point (cell coordinates) within hearing distance.
  std::vector<Visible> VisibleNodes(const Eigen::Vector2d& cell_point) const;
  // VisibleNodes through `memo` (when not null).
  std::vector<Visible> VisibleNodes(const Eigen::Vector2d& cell_point, VisibilityMemo* memo) const;
  // The path between two points in cell coordinates, given the graph nodes each sees (called
  // only when the line of sight is blocked).
  SoundPath Between(const Eigen::Vector2d& s, const Eigen::Vector2d& r,
                    const std::function<const std::vector<Visible>&()>& seen_from_s,
                    const std::function<const std::vector<Visible>&()>& seen_from_r) const;
  SoundPath MakePath(std::vector<Eigen::Vector2d> cell_polyline, double length_cells) const;

  grid::OccupancyMap map_;
  PropagationOptions options_;
  std::vector<Eigen::Vector2i> points_;
  std::unique_ptr<VisibilityGraph> graph_;
  std::unique_ptr<CornerDistances> distances_;
  std::unique_ptr<CornerShadows> shadows_;
  double hearing_distance_ = 0.0;  // m
};

}  // namespace audio_propagation
