#include "audio_propagation/direction_errors.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include "grid/pose2d.h"
#include "nava_modem/direction_estimator.h"
#include "tool_args/number_text.h"

namespace audio_propagation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string Where(const DirectionCell& c) { return "the cell at RT60 " + multirobot_audio::tools::NumberText(c.rt60) + " s, DRR " + multirobot_audio::tools::NumberText(c.drr_db) + " dB"; }

const std::vector<DirectionSample>& Of(const DirectionCell& c, bool omni) { return omni ? c.omni : c.bidirectional; }

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

DirectionErrors::DirectionErrors(std::string profile, std::vector<DirectionCell> cells, std::size_t min_packets)
    : profile_(std::move(profile)), cells_(std::move(cells)), min_packets_(min_packets) {
  if (cells_.empty()) throw std::invalid_argument("a direction table needs at least one cell");
  if (min_packets_ < 1) throw std::invalid_argument("a direction table's cells need at least 1 packet to be drawn from");
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
        throw std::invalid_argument("the grid has a hole: no cell at RT60 " + multirobot_audio::tools::NumberText(r) + " s, DRR " + multirobot_audio::tools::NumberText(d) +
                                    " dB (expected every RT60 with every DRR)");
      }
    }
  }
  rt60s_ = Sorted(rt60s);
  drrs_ = Sorted(drrs);
  // Every cell with too few packets must find one with enough: at the driest DRR at least.
  for (const bool omni : {true, false}) {
    const bool some = std::any_of(cells_.begin(), cells_.end(), [&](const DirectionCell& c) {
      return c.drr_db == drrs_.back() && Of(c, omni).size() >= min_packets_;
    });
    if (!some) {
      throw std::invalid_argument("no cell at the driest DRR (" + multirobot_audio::tools::NumberText(drrs_.back()) + " dB) has " +
                                  std::to_string(min_packets_) + " packets for the " + (omni ? "omni" : "bidirectional") +
                                  " array; a cell with fewer draws from one that has");
    }
  }
}

const DirectionCell& DirectionErrors::Nearest(double rt60, double drr_db) const {
  const double r = NearestValue(rt60s_, std::max(rt60, 1e-3),
                                [](double a, double v) { return std::abs(std::log(a / v)); });
  const double d = NearestValue(drrs_, drr_db, [](double a, double v) { return std::abs(a - v); });
  return *std::find_if(cells_.begin(), cells_.end(), [&](const DirectionCell& c) { return c.rt60 == r && c.drr_db == d; });
}

const std::vector<DirectionSample>& DirectionErrors::Packets(world_sim::Microphone microphone, double rt60,
                                                             double drr_db) const {
  const bool omni = microphone == world_sim::Microphone::kOmni;
  const DirectionCell& nearest = Nearest(rt60, drr_db);
  if (Of(nearest, omni).size() >= min_packets_) return Of(nearest, omni);
  // The same DRR at the nearest RT60 (by ratio) with enough; else the next drier DRR's.
  for (auto d = std::lower_bound(drrs_.begin(), drrs_.end(), nearest.drr_db); d != drrs_.end(); ++d) {
    const DirectionCell* best = nullptr;
    for (const DirectionCell& c : cells_) {
      if (c.drr_db != *d || Of(c, omni).size() < min_packets_) continue;
      if (!best || std::abs(std::log(c.rt60 / nearest.rt60)) < std::abs(std::log(best->rt60 / nearest.rt60))) best = &c;
    }
    if (best) return Of(*best, omni);
  }
  return Of(nearest, omni);  // unreachable: the constructor checks the driest DRR
}

SensedDirection DirectionErrors::Sense(world_sim::Microphone microphone, double relative, double drr_db, double rt60,
                                       std::mt19937& rng) const {
  if (microphone == world_sim::Microphone::kNone || !std::isfinite(relative)) return {kNaN, 0.0};
  const std::vector<DirectionSample>& packets =
      Packets(microphone, std::isfinite(rt60) ? rt60 : rt60s_.back(), std::isfinite(drr_db) ? drr_db : drrs_.front());
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
  const bool right = nava_modem::SameEndOfAxis(s.truth, s.estimate);
  const bool front = std::cos(relative) >= 0.0;
  return {front == right ? 0.0 : M_PI, s.confidence};
}

}  // namespace audio_propagation
