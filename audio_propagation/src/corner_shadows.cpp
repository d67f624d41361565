#include "audio_propagation/corner_shadows.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <thread>

namespace audio_propagation {
namespace {

constexpr float kNever = std::numeric_limits<float>::infinity();
// Coverage is tracked on finer sub-sectors, so that a far wall whose boxes are each narrower
// than a sector still covers it.
constexpr int kSubsPerSector = 4;
constexpr int kSubs = CornerShadows::kSectors * kSubsPerSector;
constexpr double kSubWidth = 4.0 / kSubs;  // in pseudo-angle units
// A box covers a sub-sector only when its silhouette reaches this far (pseudo-angle units,
// about a microradian) beyond both edges of it: the rays in the sub-sector then pass at least
// that angle inside the box's outline, far from the grazing cases the exact rules let through.
constexpr double kAngleMargin = 1e-6;
// Added to every shadow distance (cells), against rounding in the distance comparison.
constexpr double kDistanceMargin = 1e-3;

// Blocking cells on the map with a free 8-neighbour: a ray from a free point meets one of these
// first wherever it enters a wall.
bool IsWallCell(const grid::OccupancyMap& map, int i, int j) {
  if (!map.Blocks(i, j)) return false;
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di)
      if (map.InBounds(i + di, j + dj) && !map.Blocks(i + di, j + dj)) return true;
  return false;
}

}  // namespace

// Runs of blocking cells along each row, cut at every kBoxSide-th column, are stacked with the
// identical runs of up to kBoxSide rows above them into boxes. A box is kept when it holds a
// wall cell: boxes deep inside a wall are never reached first.
std::vector<CornerShadows::Box> CornerShadows::WallBoxes(const grid::OccupancyMap& map) {
  std::vector<Box> out;
  for (int y0 = 0; y0 < map.height(); y0 += kBoxSide) {
    const int y_end = std::min(map.height(), y0 + kBoxSide);
    for (int x0 = 0; x0 < map.width(); x0 += kBoxSide) {
      const int x_end = std::min(map.width(), x0 + kBoxSide);
      std::vector<Box> open;  // boxes of this tile still growing upwards
      for (int y = y0; y < y_end; ++y) {
        std::vector<Box> next;
        for (int x = x0; x < x_end;) {
          if (!map.Blocks(x, y)) {
            ++x;
            continue;
          }
          int e = x;
          while (e < x_end && map.Blocks(e, y)) ++e;
          bool wall = false;
          for (int i = x; i < e && !wall; ++i) wall = IsWallCell(map, i, y);
          auto same = std::find_if(open.begin(), open.end(), [&](const Box& b) { return b.x0 == x && b.x1 == e; });
          if (same != open.end()) {
            Box grown = *same;
            grown.y1 = y + 1;
            grown.wall = grown.wall || wall;
            open.erase(same);
            next.push_back(grown);
          } else {
            next.push_back({x, y, e, y + 1, wall});
          }
          x = e;
        }
        for (const Box& b : open) {
          if (b.wall) out.push_back(b);
        }
        open = std::move(next);
      }
      for (const Box& b : open) {
        if (b.wall) out.push_back(b);
      }
    }
  }
  return out;
}

namespace {

// Smallest open sub-sector index >= i (kSubs when none), with path halving.
int FindOpen(std::vector<int>& next_open, int i) {
  while (next_open[i] != i) {
    next_open[i] = next_open[next_open[i]];
    i = next_open[i];
  }
  return i;
}

}  // namespace

double PseudoAngle(double x, double y) {
  if (y >= 0.0) return x >= 0.0 ? y / (x + y) : 1.0 - x / (y - x);
  return x < 0.0 ? 2.0 - y / (-x - y) : 3.0 + x / (x - y);
}

CornerShadows::CornerShadows(const grid::OccupancyMap& map,
                             const std::vector<Eigen::Vector2d>& corners, int threads)
    : corners_(corners), shadow_(corners.size() * kSectors, kNever) {
  const std::vector<Box> boxes = WallBoxes(map);
  threads = std::max(1, threads);
  auto work = [&](int t) {
    std::vector<float> sub_far(kSubs);
    std::vector<int> next_open(kSubs + 1);
    for (std::size_t k = t; k < corners_.size(); k += threads) BuildCorner(k, boxes, sub_far, next_open);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& th : pool) th.join();
}

void CornerShadows::BuildCorner(std::size_t k, const std::vector<Box>& boxes,
                                std::vector<float>& sub_far, std::vector<int>& next_open) {
  const Eigen::Vector2d c = corners_[k];
  // Nearest boxes first (bucketed by whole cells of distance), so that each sub-sector is
  // covered by about the nearest box that can cover it.
  std::vector<float> near(boxes.size());
  int max_bucket = 0;
  for (std::size_t n = 0; n < boxes.size(); ++n) {
    const Box& w = boxes[n];
    const double dx = std::max({w.x0 - c.x(), 0.0, c.x() - w.x1});
    const double dy = std::max({w.y0 - c.y(), 0.0, c.y() - w.y1});
    near[n] = static_cast<float>(std::sqrt(dx * dx + dy * dy));
    max_bucket = std::max(max_bucket, static_cast<int>(near[n]));
  }
  std::vector<int> start(max_bucket + 2, 0);
  for (float d : near) ++start[static_cast<int>(d) + 1];
  for (int b = 0; b <= max_bucket; ++b) start[b + 1] += start[b];
  std::vector<int> order(boxes.size());
  for (std::size_t n = 0; n < boxes.size(); ++n) order[start[static_cast<int>(near[n])]++] = static_cast<int>(n);

  std::fill(sub_far.begin(), sub_far.end(), kNever);
  for (int i = 0; i <= kSubs; ++i) next_open[i] = i;
  int open = kSubs;
  auto cover = [&](int first, int last, float far) {  // sub-sectors first..last, in range
    for (int s = FindOpen(next_open, first); s <= last; s = FindOpen(next_open, s)) {
      sub_far[s] = far;
      next_open[s] = s + 1;
      --open;
    }
  };

  for (int n : order) {
    // The silhouette of the box seen from the corner. A box holding the wall cell whose corner
    // this is has the corner as a vertex; the rays strictly inside its silhouette still enter it.
    const Box& w = boxes[n];
    std::array<double, 4> angle;
    int count = 0;
    double far2 = 0.0;
    for (int v = 0; v < 4; ++v) {
      const Eigen::Vector2d d((v & 1 ? w.x1 : w.x0) - c.x(), (v & 2 ? w.y1 : w.y0) - c.y());
      if (d.squaredNorm() == 0.0) continue;
      angle[count++] = PseudoAngle(d.x(), d.y());
      far2 = std::max(far2, d.squaredNorm());
    }
    const auto end = angle.begin() + count;
    double lo = *std::min_element(angle.begin(), end);
    double hi = *std::max_element(angle.begin(), end);
    if (hi - lo > 2.0) {  // the silhouette (under half a turn) straddles angle 0
      for (auto a = angle.begin(); a != end; ++a) *a += *a < 2.0 ? 4.0 : 0.0;
      lo = *std::min_element(angle.begin(), end);
      hi = *std::max_element(angle.begin(), end);
    }
    const int first = static_cast<int>(std::ceil((lo + kAngleMargin) / kSubWidth));
    const int last = static_cast<int>(std::floor((hi - kAngleMargin) / kSubWidth)) - 1;
    if (last < first) continue;
    const float far = static_cast<float>(std::sqrt(far2) + kDistanceMargin);
    if (last < kSubs) {
      cover(first, last, far);
    } else if (first >= kSubs) {
      cover(first - kSubs, last - kSubs, far);
    } else {
      cover(first, kSubs - 1, far);
      cover(0, last - kSubs, far);
    }
    if (open == 0) break;
  }

  float* out = &shadow_[k * kSectors];
  for (int s = 0; s < kSectors; ++s) {
    float worst = 0.0f;
    for (int u = 0; u < kSubsPerSector; ++u) worst = std::max(worst, sub_far[s * kSubsPerSector + u]);
    out[s] = worst * worst;  // squared; +inf stays +inf
  }
}

bool CornerShadows::Hidden(std::size_t k, const Eigen::Vector2d& point) const {
  const Eigen::Vector2d d = point - corners_[k];
  const double r2 = d.squaredNorm();
  if (r2 < 1e-12) return false;
  const int s = std::min(kSectors - 1, static_cast<int>(PseudoAngle(d.x(), d.y()) * (kSectors / 4.0)));
  return r2 > shadow_[k * kSectors + s];
}

double CornerShadows::CoveredFraction() const {
  std::size_t covered = 0;
  for (float v : shadow_) covered += std::isfinite(v);
  return shadow_.empty() ? 0.0 : static_cast<double>(covered) / shadow_.size();
}

}  // namespace audio_propagation
