#include "ranging/two_way_ranger.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace ranging {
namespace {

// A packet's timings by one listener this close together are one report given twice, not the
// payload sent again.
constexpr double kSameReportS = 1e-6;
// Packets kept at most (a team's traffic over twice the window is far less).
constexpr std::size_t kMaxPackets = 1024;
// A teammate's clock is told from the median of its latest rate errors as heard...
constexpr std::size_t kRateHistory = 9;
// ...until its packets timed both by it and by this robot span this long (RateOf).
constexpr double kMinRateSpanS = 2.0;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void Require(bool ok, const std::string& field, double value, const std::string& expected) {
  if (!ok || !std::isfinite(value)) {
    throw std::invalid_argument("ranger " + field + " " + std::to_string(value) + ": expected " + expected);
  }
}

}  // namespace

void ValidateRangerOptions(const RangerOptions& o) {
  Require(o.speed_of_sound >= 100.0 && o.speed_of_sound <= 2000.0, "speed_of_sound", o.speed_of_sound, "100 to 2000 m/s");
  Require(o.pair_window > 0.0, "pair_window", o.pair_window, "above 0 s");
  Require(o.max_rate_error >= 0.0 && o.max_rate_error <= 0.05, "max_rate_error", o.max_rate_error, "0 to 0.05");
  Require(o.samples >= 1, "samples", o.samples, "at least 1");
  Require(o.max_age > 0.0, "max_age", o.max_age, "above 0 s");
  Require(o.max_range > 0.0, "max_range", o.max_range, "above 0 m");
  Require(std::abs(o.offset) <= 10.0, "offset", o.offset, "-10 to 10 m");
  Require(o.sample_std > 0.0, "sample_std", o.sample_std, "above 0 m");
}

TwoWayRanger::TwoWayRanger(std::string self, std::vector<std::string> team, const RangerOptions& options)
    : self_(std::move(self)), team_(std::move(team)), options_(options) {
  ValidateRangerOptions(options_);
  if (self_.empty()) throw std::invalid_argument("ranger: expected this robot's name, got none");
  if (!team_.empty() && std::find(team_.begin(), team_.end(), self_) == team_.end()) team_.push_back(self_);
}

void TwoWayRanger::Add(const Timing& t) {
  const auto known = [&](const std::string& robot) {
    return !robot.empty() && (team_.empty() || std::find(team_.begin(), team_.end(), robot) != team_.end());
  };
  if (!known(t.sender) || !known(t.listener)) {
    ++refused_.unknown_robot;
    return;
  }
  if (IsAnnouncement(t)) {
    Packet* p = Find(t.sender, t.data, t.stamp);
    if (!p) p = &NewPacket(t.sender, t.data);
    p->announced = latest_announcement_ += 1.0;
    return;
  }
  const auto epoch = epoch_.find(t.listener);
  if (epoch != epoch_.end() && t.clock_epoch < epoch->second) {
    ++refused_.backwards;
    return;
  }
  if (epoch == epoch_.end() || t.clock_epoch > epoch->second) {
    if (epoch != epoch_.end()) Restart(t.listener);
    epoch_[t.listener] = t.clock_epoch;
  }
  if (!std::isfinite(t.arrival)) {
    ++refused_.backwards;
    return;
  }
  const bool own = t.sender == t.listener;
  if (!std::isfinite(t.rate_error) || (!own && std::abs(t.rate_error) > options_.max_rate_error)) {
    ++refused_.bad_rate;
    return;
  }
  auto last = last_arrival_.find(t.listener);
  if (last != last_arrival_.end() && t.arrival < last->second) {
    ++refused_.backwards;
    return;
  }
  last_arrival_[t.listener] = t.arrival;
  Forget();

  Packet* found = Find(t.sender, t.data, t.stamp);
  Packet& packet = found ? *found : NewPacket(t.sender, t.data);
  const auto before = packet.heard.find(t.listener);
  if (before != packet.heard.end()) {
    // One listener timing one sender's payload twice within the window: the payload was sent
    // again, and which timing goes with which copy cannot be told. (A report repeated as it was
    // is dropped quietly.)
    if (std::abs(before->second.arrival - t.arrival) > kSameReportS) {
      ++refused_.repeated_payload;
      packet.repeated = true;
    }
    return;
  }
  packet.heard[t.listener] = t;
  if (!own && t.listener == self_) {
    auto& rates = rates_[t.sender];
    rates.push_back(t.rate_error);
    if (rates.size() > kRateHistory) rates.erase(rates.begin());
  }
  if (packet.repeated) return;
  // The teammates whose exchange with this robot this timing may complete, each once (one
  // exchange is one sample, however many others timed the packet).
  if (t.listener != self_) {
    if (packet.sender == self_ || packet.sender == t.listener) Pair(packet, t.listener);
  } else if (packet.sender != self_) {
    Pair(packet, packet.sender);
  } else {
    for (const auto& [listener, timing] : packet.heard) {
      if (listener != self_) Pair(packet, listener);
    }
  }
}

// With `packet` one half of an exchange between this robot and `teammate`, the other half
// closest in time (on this robot's clock) within the window completes it.
void TwoWayRanger::Pair(const Packet& packet, const std::string& teammate) {
  if (teammate == self_) return;
  const bool mine = packet.sender == self_;
  if (!mine && packet.sender != teammate) return;
  const auto a = packet.heard.find(self_), b = packet.heard.find(teammate);
  if (a == packet.heard.end() || b == packet.heard.end()) return;
  const Packet* best = nullptr;
  double best_gap = options_.pair_window;
  for (const Packet& other : packets_) {
    if (other.repeated || other.sender != (mine ? teammate : self_)) continue;
    const auto oa = other.heard.find(self_), ob = other.heard.find(teammate);
    if (oa == other.heard.end() || ob == other.heard.end()) continue;
    const double gap = std::abs(oa->second.arrival - a->second.arrival);
    if (gap <= best_gap) best_gap = gap, best = &other;
  }
  if (!best) return;
  const Packet& p = mine ? packet : *best;  // this robot's packet
  const Packet& q = mine ? *best : packet;  // the teammate's
  const double a1 = p.heard.at(self_).arrival, b1 = p.heard.at(teammate).arrival;
  const double b2 = q.heard.at(teammate).arrival, a2 = q.heard.at(self_).arrival;
  const double rho = RateOf(teammate);
  const double round_trip = ((a2 - a1) - (b2 - b1) / (1.0 + rho)) / (1.0 + own_rate_error_);
  const double range = options_.speed_of_sound / 2.0 * round_trip + options_.offset;
  if (!(range >= -1.0 && range <= options_.max_range)) {
    ++refused_.implausible;
    return;
  }
  auto& samples = samples_[teammate];
  samples.push_back(Sampled{range, std::max(a1, a2)});
  if (static_cast<int>(samples.size()) > options_.samples) samples.erase(samples.begin());
}

TwoWayRanger::Packet* TwoWayRanger::Find(const std::string& sender, const std::vector<std::uint8_t>& data, double stamp) {
  for (auto it = packets_.rbegin(); it != packets_.rend(); ++it) {
    if (it->sender != sender || it->data != data) continue;
    bool stamped = false, near = false;
    for (const auto& [listener, timing] : it->heard) {
      if (std::isnan(timing.stamp)) continue;
      stamped = true;
      near = near || std::abs(timing.stamp - stamp) <= kSamePacketS;
    }
    if (std::isnan(stamp) || !stamped || near) return &*it;
  }
  return nullptr;
}

TwoWayRanger::Packet& TwoWayRanger::NewPacket(const std::string& sender, const std::vector<std::uint8_t>& data) {
  if (packets_.size() == kMaxPackets) packets_.erase(packets_.begin());
  packets_.push_back(Packet{sender, data, {}, false, 0.0});
  return packets_.back();
}

std::optional<std::string> TwoWayRanger::SenderOf(const std::vector<std::uint8_t>& data) const {
  std::optional<std::string> sender;
  for (const Packet& p : packets_) {
    if (p.data != data || (p.announced == 0.0 && !p.heard.count(p.sender))) continue;
    if (sender && *sender != p.sender) return std::nullopt;  // two robots sent it
    sender = p.sender;
  }
  return sender;
}

// The teammate's clock over ours, minus 1: from its own timings of its packets against ours of
// the same packets (a line through them: its slope is the clocks' ratio, good to a few ppm over
// seconds), where they span long enough; else from what our receiver measured on its packets
// (the room profile's chirps give some 30 ppm, nava's bit clock only 0.1 %).
double TwoWayRanger::RateOf(const std::string& teammate) const {
  double n = 0.0, sb = 0.0, sa = 0.0, sbb = 0.0, sba = 0.0, lo = 1e300, hi = -1e300, origin_b = 0.0, origin_a = 0.0;
  for (const Packet& p : packets_) {
    if (p.repeated || p.sender != teammate) continue;
    const auto b = p.heard.find(teammate), a = p.heard.find(self_);
    if (b == p.heard.end() || a == p.heard.end()) continue;
    // Relative to the first, so that clocks far from zero keep their precision.
    const double x = b->second.arrival, y = a->second.arrival;
    if (n == 0.0) origin_b = x, origin_a = y;
    const double dx = x - origin_b, dy = y - origin_a;
    n += 1.0, sb += dx, sa += dy, sbb += dx * dx, sba += dx * dy;
    lo = std::min(lo, x), hi = std::max(hi, x);
  }
  if (n >= 2.0 && hi - lo >= kMinRateSpanS) {
    const double slope = (n * sba - sb * sa) / (n * sbb - sb * sb);
    const double rho = 1.0 / slope - 1.0;
    if (std::isfinite(rho) && std::abs(rho) <= options_.max_rate_error) return rho;
  }
  const auto heard = rates_.find(teammate);
  return heard == rates_.end() || heard->second.empty() ? 0.0 : Median(heard->second);
}

// A listener's clock restarted: its timings are on a clock that no longer runs.
void TwoWayRanger::Restart(const std::string& listener) {
  for (Packet& p : packets_) p.heard.erase(listener);
  last_arrival_.erase(listener);
}

// Packets older than twice the window on every clock that timed them can pair with nothing new;
// announced packets no one timed go after kMaxPackets newer ones.
void TwoWayRanger::Forget() {
  packets_.erase(std::remove_if(packets_.begin(), packets_.end(),
                                [&](const Packet& p) {
                                  if (p.heard.empty()) return p.announced < latest_announcement_ - kMaxPackets;
                                  for (const auto& [listener, timing] : p.heard) {
                                    if (last_arrival_.at(listener) - timing.arrival <= 2.0 * options_.pair_window) return false;
                                  }
                                  return true;
                                }),
                 packets_.end());
}

std::optional<Range> TwoWayRanger::RangeTo(const std::string& teammate, double now) const {
  const auto it = samples_.find(teammate);
  if (it == samples_.end()) return std::nullopt;
  std::vector<double> ranges;
  double latest = -std::numeric_limits<double>::infinity();
  for (const Sampled& s : it->second) {
    if (now - s.at > options_.max_age) continue;
    ranges.push_back(s.range);
    latest = std::max(latest, s.at);
  }
  if (ranges.empty()) return std::nullopt;
  Range r;
  r.teammate = teammate;
  r.range = Median(ranges);
  r.samples = static_cast<int>(ranges.size());
  // The samples' own spread where there are several, never below one sample's uncertainty; the
  // median of n samples is about as sure as their mean.
  double spread = 0.0;
  for (double x : ranges) spread += (x - r.range) * (x - r.range);
  const double per_sample = ranges.size() > 1 ? std::sqrt(spread / static_cast<double>(ranges.size() - 1)) : 0.0;
  r.range_std = std::max(per_sample, options_.sample_std) / std::sqrt(static_cast<double>(ranges.size()));
  r.age = std::max(0.0, now - latest);
  return r;
}

std::vector<Range> TwoWayRanger::Ranges(double now) const {
  std::vector<Range> out;
  for (const auto& [teammate, samples] : samples_) {
    if (auto r = RangeTo(teammate, now)) out.push_back(*r);
  }
  return out;
}

}  // namespace ranging
