#include "world_sim/lockstep_inbox.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace world_sim {

void LockstepInbox::Arrive(const StreamId& stream, Delivery deliver) {
  if (counted_known_ && counted_.count(stream.publisher) == 0) {
    deliver();
    return;
  }
  if (held_count_ >= capacity_) {
    // Bounded: rather than grow without end, hand on the oldest held message now.
    for (auto& [id, s] : streams_) {
      if (s.held.empty()) continue;
      Delivery oldest = std::move(s.held.front());
      s.held.pop_front();
      ++s.handed;
      --held_count_;
      ++overflow_;
      oldest();
      break;
    }
  }
  streams_[stream].held.push_back(std::move(deliver));
  ++held_count_;
}

void LockstepInbox::HandUncounted() {
  for (auto& [id, s] : streams_) {
    if (counted_.count(id.publisher) > 0) continue;
    while (!s.held.empty()) {
      Delivery d = std::move(s.held.front());
      s.held.pop_front();
      ++s.handed;
      --held_count_;
      d();
    }
  }
}

void LockstepInbox::Order(const StepOrder& order, const std::vector<std::string>& counted_publishers) {
  if (!counted_publishers.empty()) {
    counted_ = std::set<std::string>(counted_publishers.begin(), counted_publishers.end());
    counted_known_ = true;
    HandUncounted();
  }
  for (const StreamCount& c : order.totals) allowed_[c.stream] = c.total;
  order_ = order;
  has_order_ = true;
}

bool LockstepInbox::Ready() const {
  if (!has_order_) return false;
  for (const auto& [id, total] : allowed_) {
    const auto s = streams_.find(id);
    const std::uint64_t arrived = s == streams_.end() ? 0 : s->second.handed + s->second.held.size();
    if (arrived < total) return false;
  }
  return true;
}

void LockstepInbox::Run() {
  for (const auto& [id, total] : allowed_) {
    auto s = streams_.find(id);
    if (s == streams_.end()) continue;
    Stream& stream = s->second;
    while (stream.handed < total && !stream.held.empty()) {
      Delivery d = std::move(stream.held.front());
      stream.held.pop_front();
      ++stream.handed;
      --held_count_;
      d();
    }
  }
  has_order_ = false;
  RunTimers(order_.time);
}

void LockstepInbox::AddTimer(double period, double start, TimerCallback callback, std::function<double()> rest_until) {
  timers_.push_back(Timer{period, start, 1, start + period, start > 0.0, std::move(callback), std::move(rest_until)});
}

void LockstepInbox::RunTimers(double now) {
  for (Timer& t : timers_) {
    if (!t.anchored) {
      t.anchor = now;
      t.due = now + t.period;
      t.anchored = true;
    }
  }
  // Each timer due by `now` fires once (a timer slower than the step fires at most once a
  // step, as a ROS timer does when the clock jumps), earliest due first, ties in creation order.
  std::vector<bool> fired(timers_.size(), false);
  for (;;) {
    std::size_t best = timers_.size();
    for (std::size_t i = 0; i < timers_.size(); ++i) {
      if (fired[i] || timers_[i].due > now + 1e-9) continue;
      if (best == timers_.size() || timers_[i].due < timers_[best].due) best = i;
    }
    if (best == timers_.size()) break;
    fired[best] = true;
    Timer& t = timers_[best];
    const double expected = t.due;
    // The next due time is the first multiple of the period after now (with the tolerance
    // above: a due time within it counts as now and must not fire again next step).
    const double passed = std::floor((now + 1e-9 - t.anchor) / t.period);
    t.periods = std::max(t.periods + 1, static_cast<std::uint64_t>(std::max(passed, 0.0)) + 1);
    t.due = t.anchor + static_cast<double>(t.periods) * t.period;
    t.callback(expected, now);
  }
}

double LockstepInbox::NextDue() const {
  double next = std::numeric_limits<double>::infinity();
  for (const Timer& t : timers_) {
    if (!t.anchored) return 0.0;
    next = std::min(next, t.rest_until ? std::max(t.due, t.rest_until()) : t.due);
  }
  return next;
}

}  // namespace world_sim
