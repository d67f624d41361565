#include "audio_propagation/propagation_model.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "audio_propagation/path_cache.h"
#include "grid/line_of_sight.h"

namespace audio_propagation {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("audio_propagation: " + what);
}

}  // namespace

void ValidateOptions(const PropagationOptions& o) {
  Require(std::isfinite(o.source_level_db), "source_level_db must be a finite number of dB");
  Require(std::isfinite(o.threshold_db) && o.threshold_db <= o.source_level_db,
          "threshold_db (" + std::to_string(o.threshold_db) +
              ") must be finite and not above source_level_db (" + std::to_string(o.source_level_db) + ")");
  Require(o.reference_distance > 0.0 && std::isfinite(o.reference_distance),
          "reference_distance must be a positive number of metres");
  Require(o.max_range >= 0.0 && std::isfinite(o.max_range),
          "max_range must be >= 0 m (0 = no limit), got " + std::to_string(o.max_range));
  Require(o.speed_of_sound > 0.0 && std::isfinite(o.speed_of_sound),
          "speed_of_sound must be a positive number of m/s");
  Require(o.threads >= 1 && o.threads <= 256, "threads must be from 1 to 256");
}

PropagationModel::PropagationModel(grid::OccupancyMap map, const PropagationOptions& options)
    : map_(std::move(map)), options_(options) {
  ValidateOptions(options_);
  hearing_distance_ = options_.reference_distance *
                      std::pow(10.0, (options_.source_level_db - options_.threshold_db) / 20.0);
  if (options_.max_range > 0.0) hearing_distance_ = std::min(hearing_distance_, options_.max_range);
  points_ = FindDiffractionPoints(map_, options_.rule);
  graph_ = std::make_unique<VisibilityGraph>(map_, CornerVertices(map_, points_),
                                             hearing_distance_ / map_.resolution(),
                                             options_.threads);
  distances_ = std::make_unique<CornerDistances>(*graph_, hearing_distance_ / map_.resolution(),
                                                 options_.threads);
  shadows_ = std::make_unique<CornerShadows>(map_, graph_->positions(), options_.threads);
}

double PropagationModel::LevelAt(double length) const {
  const double d0 = options_.reference_distance;
  return options_.source_level_db - 20.0 * std::log10(std::max(length, d0) / d0);
}

std::vector<PropagationModel::Visible> PropagationModel::VisibleNodes(const Eigen::Vector2d& p) const {
  std::vector<Visible> out;
  const double reach = hearing_distance_ / map_.resolution();
  const double reach2 = reach * reach;
  for (std::size_t k = 0; k < graph_->size(); ++k) {
    const Eigen::Vector2d& q = graph_->position(k);
    const double d2 = (q - p).squaredNorm();
    if (d2 > reach2 || !graph_->corner(k).Tangent(q - p) || shadows_->Hidden(k, p)) continue;
    if (!grid::FirstBlockedInCells(map_, p, q)) out.push_back({static_cast<std::int32_t>(k), std::sqrt(d2)});
  }
  return out;
}

std::vector<PropagationModel::Visible> PropagationModel::VisibleNodes(const Eigen::Vector2d& p,
                                                                     VisibilityMemo* memo) const {
  const std::optional<std::uint32_t> key =
      memo ? CellKey(Eigen::Vector2i(static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y()))))
           : std::nullopt;
  if (!key) return VisibleNodes(p);
  std::vector<Visible> out;
  if (const std::vector<std::int32_t>* nodes = memo->Find(*key)) {
    out.reserve(nodes->size());
    for (const std::int32_t k : *nodes) out.push_back({k, (graph_->position(static_cast<std::size_t>(k)) - p).norm()});
    return out;
  }
  out = VisibleNodes(p);
  std::vector<std::int32_t> nodes;
  nodes.reserve(out.size());
  for (const Visible& v : out) nodes.push_back(v.node);
  memo->Insert(*key, std::move(nodes));
  return out;
}

SoundPath PropagationModel::MakePath(std::vector<Eigen::Vector2d> cells, double length_cells) const {
  SoundPath path;
  path.length = length_cells * map_.resolution();
  if (path.length > hearing_distance_ + 1e-9) return path;  // too far to be heard at all
  path.reachable = true;
  path.bends = static_cast<int>(cells.size()) - 2;
  for (Eigen::Vector2d& c : cells) c = map_.CellCoordsToWorld(c);
  path.polyline = std::move(cells);
  path.level_db = LevelAt(path.length);
  path.audible = path.level_db >= options_.threshold_db;
  const Eigen::Vector2d& at = path.polyline.back();
  const Eigen::Vector2d& from = path.polyline[path.polyline.size() - 2];
  // A listener at the source has no direction to hear it from.
  path.arrival_angle = from == at ? std::numeric_limits<double>::quiet_NaN()
                                  : std::atan2(from.y() - at.y(), from.x() - at.x());
  path.travel_time = path.length / options_.speed_of_sound;
  return path;
}

SoundPath PropagationModel::Between(const Eigen::Vector2d& s, const Eigen::Vector2d& r,
                                    const std::function<const std::vector<Visible>&()>& seen_from_s,
                                    const std::function<const std::vector<Visible>&()>& seen_from_r) const {
  const double reach = hearing_distance_ / map_.resolution();
  const double direct = (r - s).norm();
  if (direct > reach) return {};
  if (!grid::FirstBlockedInCells(map_, s, r)) return MakePath({s, r}, direct);
  // Around walls: source -> a corner it sees -> ... -> a corner the listener sees -> listener.
  double best = kInf;
  std::int32_t first = -1, last = -1;
  for (const Visible& a : seen_from_s()) {
    if (a.distance >= best) continue;
    for (const Visible& b : seen_from_r()) {
      const double d = a.distance + distances_->distance(a.node, b.node) + b.distance;
      if (d < best) {
        best = d;
        first = a.node;
        last = b.node;
      }
    }
  }
  if (first < 0 || best > reach) return {};
  std::vector<Eigen::Vector2d> poly = {s};
  distances_->AppendPath(*graph_, first, last, poly);
  poly.push_back(r);
  return MakePath(std::move(poly), best);
}

std::vector<std::vector<SoundPath>> PropagationModel::Compute(
    const std::vector<Eigen::Vector2d>& positions, const std::vector<bool>& sources) const {
  const std::size_t n = positions.size();
  std::vector<std::vector<SoundPath>> result(n, std::vector<SoundPath>(n));
  std::vector<Eigen::Vector2d> cells(n);
  for (std::size_t k = 0; k < n; ++k) cells[k] = map_.WorldToCellCoords(positions[k]);

  // Which graph nodes each listener sees, computed only for listeners that need the graph.
  std::vector<std::vector<Visible>> visible(n);
  std::vector<bool> visible_known(n, false);
  auto visible_of = [&](std::size_t k) -> const std::vector<Visible>& {
    if (!visible_known[k]) {
      visible[k] = VisibleNodes(cells[k]);
      visible_known[k] = true;
    }
    return visible[k];
  };

  for (std::size_t s = 0; s < n; ++s) {
    if (s >= sources.size() || !sources[s]) continue;
    for (std::size_t r = 0; r < n; ++r) {
      if (r == s) continue;
      result[s][r] = Between(cells[s], cells[r], [&]() -> const std::vector<Visible>& { return visible_of(s); },
                             [&]() -> const std::vector<Visible>& { return visible_of(r); });
    }
  }
  return result;
}

std::vector<SoundPath> PropagationModel::From(const Eigen::Vector2d& source,
                                              const std::vector<Eigen::Vector2d>& listeners,
                                              VisibilityMemo* memo) const {
  const Eigen::Vector2d s = map_.WorldToCellCoords(source);
  std::vector<Visible> seen_from_s;
  bool known = false;
  auto from_s = [&]() -> const std::vector<Visible>& {
    if (!known) seen_from_s = VisibleNodes(s, memo), known = true;
    return seen_from_s;
  };
  std::vector<SoundPath> out;
  out.reserve(listeners.size());
  for (const Eigen::Vector2d& listener : listeners) {
    const Eigen::Vector2d r = map_.WorldToCellCoords(listener);
    std::vector<Visible> seen_from_r;
    bool r_known = false;
    out.push_back(Between(s, r, from_s, [&]() -> const std::vector<Visible>& {
      if (!r_known) seen_from_r = VisibleNodes(r, memo), r_known = true;
      return seen_from_r;
    }));
  }
  return out;
}

SoundPath PropagationModel::Path(const Eigen::Vector2d& from, const Eigen::Vector2d& to) const {
  return Compute({from, to}, {true, false})[0][1];
}

}  // namespace audio_propagation
