#include "grid/room_segmentation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

namespace grid {
namespace {

constexpr int kBlocked = -1;
constexpr int kUnlabelled = -2;

void Validate(const OccupancyMap& map, const RoomSegmentationOptions& o) {
  if (!std::isfinite(o.door_half_width) || o.door_half_width < map.resolution()) {
    throw std::invalid_argument("room segmentation: door_half_width must be at least one cell (" +
                                std::to_string(map.resolution()) + " m), got " + std::to_string(o.door_half_width));
  }
  if (!(o.min_room_area >= 0.0) || !std::isfinite(o.min_room_area)) {
    throw std::invalid_argument("room segmentation: min_room_area must be >= 0 m^2, got " +
                                std::to_string(o.min_room_area));
  }
  if (!(o.max_obstacle_size >= 0.0) || !std::isfinite(o.max_obstacle_size)) {
    throw std::invalid_argument("room segmentation: max_obstacle_size must be >= 0 m, got " +
                                std::to_string(o.max_obstacle_size));
  }
}

// Cells of each label (label >= 0), by flat index.
std::vector<std::vector<int>> CellsOf(const std::vector<int>& labels, int count) {
  std::vector<std::vector<int>> cells(count);
  for (std::size_t k = 0; k < labels.size(); ++k)
    if (labels[k] >= 0) cells[labels[k]].push_back(static_cast<int>(k));
  return cells;
}

// The 4-neighbours of flat cell `k` on a w x h grid.
template <typename F>
void ForNeighbours(int k, int w, int h, F&& f) {
  const int i = k % w, j = k / w;
  if (i > 0) f(k - 1);
  if (i + 1 < w) f(k + 1);
  if (j > 0) f(k - w);
  if (j + 1 < h) f(k + w);
}

// Where rooms meet (`labels`: a room per free cell, negative where blocked): the cells on either
// side of the line between two rooms, each connected run of them one opening, as wide as the run
// is long.
std::vector<SegmentedOpening> FindOpenings(const std::vector<int>& labels, const OccupancyMap& map) {
  const int w = map.width(), h = map.height();
  std::vector<SegmentedOpening> openings;
  std::map<std::pair<int, int>, std::vector<int>> sides;  // (a, b), a < b -> cells on the line
  for (int k = 0; k < w * h; ++k) {
    if (labels[k] < 0) continue;
    ForNeighbours(k, w, h, [&](int n) {
      if (labels[n] >= 0 && labels[n] != labels[k]) {
        sides[{std::min(labels[k], labels[n]), std::max(labels[k], labels[n])}].push_back(k);
      }
    });
  }
  std::vector<char> on_line(labels.size(), 0), seen(labels.size(), 0);
  for (auto& [pair, line] : sides) {
    std::sort(line.begin(), line.end());
    line.erase(std::unique(line.begin(), line.end()), line.end());
    for (int k : line) on_line[k] = 1;
    for (int start : line) {
      if (seen[start]) continue;
      // One run: the cells on the line connected through their 8-neighbours.
      std::vector<int> run{start};
      seen[start] = 1;
      for (std::size_t q = 0; q < run.size(); ++q) {
        const int i = run[q] % w, j = run[q] / w;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ni = i + di, nj = j + dj;
            if (ni < 0 || nj < 0 || ni >= w || nj >= h) continue;
            const int n = nj * w + ni;
            if (on_line[n] && !seen[n]) {
              seen[n] = 1;
              run.push_back(n);
            }
          }
      }
      // Its length: the spread of its cells along their main direction, plus a cell.
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (int k : run) mean += Eigen::Vector2d(k % w, k / w);
      mean /= static_cast<double>(run.size());
      Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
      for (int k : run) {
        const Eigen::Vector2d d = Eigen::Vector2d(k % w, k / w) - mean;
        scatter += d * d.transpose();
      }
      const Eigen::Vector2d axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(1);
      double low = 0.0, high = 0.0;
      for (int k : run) {
        const double along = (Eigen::Vector2d(k % w, k / w) - mean).dot(axis);
        low = std::min(low, along);
        high = std::max(high, along);
      }
      SegmentedOpening opening;
      opening.a = pair.first;
      opening.b = pair.second;
      opening.width = (high - low + 1.0) * map.resolution();
      opening.center = map.CellCoordsToWorld(mean + Eigen::Vector2d(0.5, 0.5));
      openings.push_back(opening);
    }
    for (int k : line) on_line[k] = seen[k] = 0;  // a corner cell may lie on another pair's line
  }
  return openings;
}

// The cells of the blocked pieces of `free` (0 blocked, 255 free, 8-connected) that touch no edge
// of the map and whose bounding box is at most `max_cells` cells long on its longer side.
std::vector<int> SmallObstacles(const cv::Mat& free, double max_cells) {
  const cv::Mat blocked = free == 0;
  cv::Mat pieces, stats, centroids;
  const int count = cv::connectedComponentsWithStats(blocked, pieces, stats, centroids, 8, CV_32S);
  const int w = free.cols, h = free.rows;
  std::vector<char> small(count, 0);
  for (int p = 1; p < count; ++p) {
    const int x = stats.at<int>(p, cv::CC_STAT_LEFT), y = stats.at<int>(p, cv::CC_STAT_TOP);
    const int bw = stats.at<int>(p, cv::CC_STAT_WIDTH), bh = stats.at<int>(p, cv::CC_STAT_HEIGHT);
    const bool edge = x == 0 || y == 0 || x + bw == w || y + bh == h;
    small[p] = !edge && std::max(bw, bh) <= max_cells;
  }
  std::vector<int> cells;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      if (small[pieces.at<int>(j, i)]) cells.push_back(j * w + i);
    }
  }
  return cells;
}

}  // namespace

RoomSegmentation::RoomSegmentation(const OccupancyMap& map, const RoomSegmentationOptions& options)
    : map_(map), width_(map.width()) {
  Validate(map, options);
  const int w = map.width(), h = map.height();
  cv::Mat free(h, w, CV_8UC1);
  labels_.assign(static_cast<std::size_t>(w) * h, kBlocked);
  int free_cells = 0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const bool open = !map.Blocks(i, j);
      free.at<std::uint8_t>(j, i) = open ? 255 : 0;
      if (open) labels_[static_cast<std::size_t>(j) * w + i] = kUnlabelled;
      free_cells += open;
    }
  }
  if (free_cells == 0) throw std::invalid_argument("room segmentation: the map has no free space");
  // Free-standing obstacles (a pillar, a table: blocked pieces that touch no edge of the map, no
  // longer than max_obstacle_size) do not divide a room: its sound fills the space round them.
  // They count as floor while the rooms are cut and grown, and are blocked again after. (By
  // length, not area: a stretch of wall between two doors is a thin piece, and it divides.)
  const std::vector<int> obstacles = SmallObstacles(free, options.max_obstacle_size / map.resolution());
  for (int k : obstacles) {
    free.at<std::uint8_t>(k / w, k % w) = 255;
    labels_[k] = kUnlabelled;
  }

  // Room cores: free space further than the door half-width from every wall.
  cv::Mat distance;
  cv::distanceTransform(free, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const cv::Mat cores = distance * map.resolution() > options.door_half_width;
  cv::Mat core_labels;
  int count = cv::connectedComponents(cores, core_labels, 8, CV_32S) - 1;  // label 0: not a core

  // The cores grow back together, a cell a step, so that each free cell joins the core nearest
  // to it along the floor.
  std::deque<int> front;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const int core = core_labels.at<int>(j, i);
      if (core > 0) {
        labels_[static_cast<std::size_t>(j) * w + i] = core - 1;
        front.push_back(j * w + i);
      }
    }
  }
  const auto grow = [&](std::deque<int>& queue) {
    while (!queue.empty()) {
      const int k = queue.front();
      queue.pop_front();
      ForNeighbours(k, w, h, [&](int n) {
        if (labels_[n] == kUnlabelled) {
          labels_[n] = labels_[k];
          queue.push_back(n);
        }
      });
    }
  };
  grow(front);
  // Free space no core reached (a space narrower than a door all round, walled off): a room of
  // its own, each connected piece.
  for (std::size_t k = 0; k < labels_.size(); ++k) {
    if (labels_[k] != kUnlabelled) continue;
    labels_[k] = count++;
    front.push_back(static_cast<int>(k));
    grow(front);
  }

  for (int k : obstacles) labels_[k] = kBlocked;

  // Rooms smaller than the smallest kept join the neighbour they share the most boundary with,
  // smallest first; one with no neighbour is a pocket no one reaches (free cells walled in, as
  // a drawn map leaves inside thick walls) and no room: its cells count as blocked.
  const double cell_area = map.resolution() * map.resolution();
  std::vector<std::vector<int>> cells = CellsOf(labels_, count);
  std::vector<int> order(count);
  for (int r = 0; r < count; ++r) order[r] = r;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return cells[a].size() < cells[b].size(); });
  for (int r : order) {
    if (static_cast<double>(cells[r].size()) * cell_area >= options.min_room_area) continue;
    std::map<int, int> shared;
    for (int k : cells[r])
      ForNeighbours(k, w, h, [&](int n) {
        if (labels_[n] >= 0 && labels_[n] != r) ++shared[labels_[n]];
      });
    if (shared.empty()) {
      for (int k : cells[r]) labels_[k] = kBlocked;
      cells[r].clear();
      continue;
    }
    const int into = std::max_element(shared.begin(), shared.end(), [](const auto& a, const auto& b) {
                       return a.second < b.second;
                     })->first;
    for (int k : cells[r]) labels_[k] = into;
    cells[into].insert(cells[into].end(), cells[r].begin(), cells[r].end());
    cells[r].clear();
  }

  // Number the rooms left 0, 1, ... and measure them.
  std::vector<int> renumber(count, -1);
  for (int r = 0; r < count; ++r) {
    if (cells[r].empty()) continue;
    renumber[r] = static_cast<int>(rooms_.size());
    SegmentedRoom room;
    room.area = static_cast<double>(cells[r].size()) * cell_area;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (int k : cells[r]) sum += map.CellCenter(k % w, k / w);
    room.centroid = sum / static_cast<double>(cells[r].size());
    rooms_.push_back(room);
  }
  for (int& label : labels_)
    if (label >= 0) label = renumber[label];

  openings_ = FindOpenings(labels_, map);
}

int RoomSegmentation::RoomAt(const Eigen::Vector2d& world) const {
  const Eigen::Vector2i c = map_.WorldToCell(world);
  if (!map_.InBounds(c.x(), c.y())) return -1;
  return RoomOfCell(c.x(), c.y());
}

}  // namespace grid
