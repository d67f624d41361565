#include "grid/reachability.h"

#include <cstdint>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace grid {

Reachability::Reachability(const OccupancyMap& map, double radius) : map_(map) {
  const int w = map.width(), h = map.height();
  cv::Mat free(h, w, CV_8UC1);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) free.at<std::uint8_t>(j, i) = map.Blocks(i, j) ? 0 : 255;
  // Euclidean distance (cells) from each free cell to the nearest blocked one.
  cv::Mat distance;
  cv::distanceTransform(free, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  cv::Mat room = distance * map.resolution() > radius;
  cv::Mat labels;
  const int count = cv::connectedComponents(room, labels, 8, CV_32S);
  labels_.assign(static_cast<std::size_t>(w) * h, 0);
  cells_.resize(count);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const int label = labels.at<int>(j, i);
      labels_[static_cast<std::size_t>(j) * w + i] = label;
      if (label > 0) cells_[label].push_back(j * w + i);
    }
  }
  for (int r = 1; r < count; ++r)
    if (largest_ == 0 || cells_[r].size() > cells_[largest_].size()) largest_ = r;
}

int Reachability::Region(const Eigen::Vector2d& point) const {
  const Eigen::Vector2i c = map_.WorldToCell(point);
  if (!map_.InBounds(c.x(), c.y())) return 0;
  return labels_[static_cast<std::size_t>(c.y()) * map_.width() + c.x()];
}

Eigen::Vector2d Reachability::Sample(int region, std::mt19937& rng) const {
  const std::vector<int>& cells = cells_.at(region);
  if (cells.empty()) throw std::invalid_argument("no room for a robot anywhere on the map");
  const int index = cells[std::uniform_int_distribution<std::size_t>(0, cells.size() - 1)(rng)];
  std::uniform_real_distribution<double> jitter(0.1, 0.9);
  return map_.CellCoordsToWorld({index % map_.width() + jitter(rng), index / map_.width() + jitter(rng)});
}

}  // namespace grid
