#include "audio_propagation/direction_errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include "grid/pose2d.h"

namespace audio_propagation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string Where(const DirectionCell& c) {
  return "the cell at RT60 " + std::to_string(c.rt60) + " s, DRR " + std::to_string(c.drr_db) + " dB";
}

void ValidateSamples(const DirectionCell& c, const std::vector<DirectionSample>& samples, const char* array) {
  for (const DirectionSample& s : samples) {
    if (!std::isfinite(s.truth) || std::isinf(s.estimate) || !(s.confidence >= 0.0 && s.confidence <= 1.0)) {
      throw std::invalid_argument(Where(c) + ", " + array + ": a packet with a true bearing or estimate not finite or a "
                                  "confidence outside 0..1");
    }
  }
}

// How far off a pair's axis (x) a sound comes from, as the three bands the pair's reports are
// drawn by: 0 within 20 degrees of broadside, 1 from 20 to 50 degrees off broadside, 2 nearer
// the axis.
int OffAxisBand(double bearing) {
  const double off = std::abs(std::remainder(bearing, M_PI));  // 0 on the axis, pi/2 broadside
  const double from_broadside = M_PI / 2 - off;
  if (from_broadside < 20.0 * M_PI / 180.0) return 0;
  if (from_broadside < 50.0 * M_PI / 180.0) return 1;
  return 2;
}

std::vector<double> Sorted(std::set<double> values) { return {values.begin(), values.end()}; }

// The grid value nearest `v` (by `distance`).
template <typename Distance>
double NearestValue(const std::vector<double>& grid, double v, Distance distance) {
  return *std::min_element(grid.begin(), grid.end(), [&](double a, double b) { return distance(a, v) < distance(b, v); });
}

}  // namespace

DirectionErrors::DirectionErrors(std::string profile, std::vector<DirectionCell> cells)
    : profile_(std::move(profile)), cells_(std::move(cells)) {
  if (cells_.empty()) throw std::invalid_argument("a direction table needs at least one cell");
  std::set<double> rt60s, drrs;
  std::set<std::pair<double, double>> places;
  for (const DirectionCell& c : cells_) {
    if (!(c.rt60 > 0.0) || !std::isfinite(c.rt60) || !std::isfinite(c.drr_db)) {
      throw std::invalid_argument(Where(c) + ": expected an RT60 above 0 s and a finite DRR");
    }
    if (!places.insert({c.rt60, c.drr_db}).second) throw std::invalid_argument(Where(c) + " is given twice");
    ValidateSamples(c, c.omni, "omni");
    ValidateSamples(c, c.bidirectional, "bidirectional");
    rt60s.insert(c.rt60);
    drrs.insert(c.drr_db);
  }
  for (double r : rt60s) {
    for (double d : drrs) {
      if (!places.count({r, d})) {
        throw std::invalid_argument("the grid has a hole: no cell at RT60 " + std::to_string(r) + " s, DRR " +
                                    std::to_string(d) + " dB (expected every RT60 with every DRR)");
      }
    }
  }
  rt60s_ = Sorted(rt60s);
  drrs_ = Sorted(drrs);
  // Every RT60's driest cell must have packets for both arrays: the wetter ones without lend theirs.
  for (double r : rt60s_) {
    const DirectionCell& driest = Nearest(r, drrs_.back());
    if (driest.omni.empty() || driest.bidirectional.empty()) {
      throw std::invalid_argument(Where(driest) + " (the driest of its RT60) has no packets for the " +
                                  (driest.omni.empty() ? "omni" : "bidirectional") +
                                  " array; a wetter cell without packets lends a drier one's");
    }
  }
}

const std::vector<DirectionSample>& DirectionErrors::Packets(world_sim::Microphone microphone, double rt60,
                                                             double drr_db) const {
  const bool omni = microphone == world_sim::Microphone::kOmni;
  const DirectionCell* cell = &Nearest(rt60, drr_db);
  // Up the DRRs of its RT60 until one has packets (the driest always has: the constructor checks).
  for (auto d = std::lower_bound(drrs_.begin(), drrs_.end(), cell->drr_db); d != drrs_.end(); ++d) {
    cell = &Nearest(cell->rt60, *d);
    if (!(omni ? cell->omni : cell->bidirectional).empty()) break;
  }
  return omni ? cell->omni : cell->bidirectional;
}

const DirectionCell& DirectionErrors::Nearest(double rt60, double drr_db) const {
  const double r = NearestValue(rt60s_, std::max(rt60, 1e-3),
                                [](double a, double v) { return std::abs(std::log(a / v)); });
  const double d = NearestValue(drrs_, drr_db, [](double a, double v) { return std::abs(a - v); });
  return *std::find_if(cells_.begin(), cells_.end(), [&](const DirectionCell& c) { return c.rt60 == r && c.drr_db == d; });
}

SensedDirection DirectionErrors::Sense(world_sim::Microphone microphone, double relative, double drr_db, double rt60,
                                       std::mt19937& rng) const {
  if (microphone == world_sim::Microphone::kNone || !std::isfinite(relative)) return {kNaN, 0.0};
  const std::vector<DirectionSample>& packets =
      Packets(microphone, std::isfinite(rt60) ? rt60 : rt60s_.front(), std::isfinite(drr_db) ? drr_db : drrs_.back());
  if (microphone == world_sim::Microphone::kOmni) {
    std::uniform_int_distribution<std::size_t> pick(0, packets.size() - 1);
    const DirectionSample& s = packets[pick(rng)];
    if (!std::isfinite(s.estimate)) return {kNaN, 0.0};
    return {grid::NormalizeAngle(relative + (s.estimate - s.truth)), s.confidence};
  }
  // The pair: a packet from as far off its axis as this sound, else any.
  const int band = OffAxisBand(relative);
  std::vector<const DirectionSample*> alike;
  for (const DirectionSample& s : packets) {
    if (OffAxisBand(s.truth) == band) alike.push_back(&s);
  }
  if (alike.empty()) {
    for (const DirectionSample& s : packets) alike.push_back(&s);
  }
  std::uniform_int_distribution<std::size_t> pick(0, alike.size() - 1);
  const DirectionSample& s = *alike[pick(rng)];
  if (!std::isfinite(s.estimate)) return {kNaN, 0.0};
  const bool right = std::cos(s.truth) * std::cos(s.estimate) > 0.0;
  const bool front = std::cos(relative) >= 0.0;
  return {front == right ? 0.0 : M_PI, s.confidence};
}

}  // namespace audio_propagation
