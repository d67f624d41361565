#include "world_sim/lockstep_coordinator.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace world_sim {

void ValidateOptions(const LockstepOptions& o) {
  if (!(o.timeout > 0.0)) {
    throw std::invalid_argument("lockstep_timeout: expected a positive number of seconds, got " +
                                std::to_string(o.timeout));
  }
  std::set<std::string> named;
  for (const std::string& name : o.participants) {
    if (name.empty()) throw std::invalid_argument("lockstep_participants: expected node names, got an empty one");
    if (!named.insert(name).second) throw std::invalid_argument("lockstep_participants: " + name + " is named twice");
  }
}

LockstepCoordinator::LockstepCoordinator(LockstepOptions options) : options_(std::move(options)) {
  ValidateOptions(options_);
  for (const std::string& name : options_.participants) participants_.emplace(name, Participant{});
}

void LockstepCoordinator::SetOwnStreams(const std::vector<std::string>& subscribed,
                                        const std::vector<std::string>& advertised) {
  own_subscribed_ = std::set<std::string>(subscribed.begin(), subscribed.end());
  own_advertised_ = std::set<std::string>(advertised.begin(), advertised.end());
}

void LockstepCoordinator::SetTotal(const StreamId& stream, std::uint64_t total) {
  std::uint64_t& known = totals_[stream];
  if (total <= known) return;
  known = total;
  grown_.insert(stream);
}

void LockstepCoordinator::OwnPublished(const std::string& topic, std::uint64_t total) {
  SetTotal(StreamId{topic, options_.self}, total);
}

void LockstepCoordinator::OwnReceived(const StreamId& stream, std::uint64_t total) {
  own_received_[stream] = total;
}

bool LockstepCoordinator::Hello(const ParticipantHello& hello) {
  auto it = participants_.find(hello.node);
  if (it == participants_.end() || it->second.dropped) return false;
  Participant& p = it->second;
  p.said_hello = true;
  p.hello = hello;
  p.subscribed = std::set<std::string>(hello.subscribed.begin(), hello.subscribed.end());
  p.passive = std::set<std::string>(hello.passive.begin(), hello.passive.end());
  for (const std::string& topic : p.subscribed) listeners_[topic].insert(hello.node);
  return true;
}

int LockstepCoordinator::KnownPublishers(const std::string& topic, const std::string& except) const {
  int n = own_advertised_.count(topic) > 0 && except != options_.self ? 1 : 0;
  for (const auto& [name, p] : participants_) {
    if (name == except || p.dropped || !p.said_hello) continue;
    for (const std::string& t : p.hello.advertised) n += t == topic ? 1 : 0;
  }
  return n;
}

bool LockstepCoordinator::Ready(const std::map<std::string, int>& own_connected, std::string* missing) const {
  std::string why;
  for (const auto& [name, p] : participants_) {
    if (p.dropped) continue;
    if (!p.said_hello) {
      why = name + " has not said hello";
    } else if (!p.hello.step_connected) {
      why = name + " is not connected to the step orders yet";
    } else {
      for (std::size_t i = 0; i < p.hello.subscribed.size() && why.empty(); ++i) {
        const int known = KnownPublishers(p.hello.subscribed[i], name);
        const int have = i < p.hello.connected.size() ? p.hello.connected[i] : 0;
        if (have < known) {
          why = name + " hears " + std::to_string(have) + " of the " + std::to_string(known) +
                " publishers of " + p.hello.subscribed[i];
        }
      }
    }
    if (!why.empty()) break;
  }
  for (auto it = own_subscribed_.begin(); why.empty() && it != own_subscribed_.end(); ++it) {
    const int known = KnownPublishers(*it, options_.self);
    const auto c = own_connected.find(*it);
    const int have = c == own_connected.end() ? 0 : c->second;
    if (have < known) {
      why = "the world hears " + std::to_string(have) + " of the " + std::to_string(known) + " publishers of " + *it;
    }
  }
  if (missing) *missing = why;
  return why.empty();
}

std::vector<std::string> LockstepCoordinator::DropUnready(const std::map<std::string, int>& own_connected) {
  std::vector<std::string> dropped;
  std::string why;
  // Drop one at a time: whoever Ready() names, until the rest are ready.
  while (!Ready(own_connected, &why)) {
    bool dropped_one = false;
    for (auto& [name, p] : participants_) {
      if (!p.dropped && why.compare(0, name.size() + 1, name + " ") == 0) {
        p.dropped = true;
        dropped.push_back(name);
        dropped_one = true;
        break;
      }
    }
    if (!dropped_one) break;  // the world itself is not connected: nothing to drop
  }
  return dropped;
}

std::vector<StepOrder> LockstepCoordinator::BeginStep(std::uint64_t step, double time, double wall_now) {
  step_ = step;
  step_wall_ = wall_now;
  // Only the streams that grew since the last orders can add to an order: a step costs what
  // happened in it, not the size of the team.
  std::map<std::string, std::vector<StreamCount>> grown_for;
  for (const StreamId& stream : grown_) {
    const std::uint64_t total = totals_[stream];
    const auto listeners = listeners_.find(stream.topic);
    if (listeners == listeners_.end()) continue;
    for (const std::string& name : listeners->second) {
      Participant& p = participants_.at(name);
      if (p.dropped || stream.publisher == name) continue;  // listeners_ holds only subscribers
      if (p.passive.count(stream.topic) > 0) {
        p.carried.insert(stream);
        continue;
      }
      std::uint64_t& told = p.told[stream];
      if (total <= told) continue;
      told = total;
      grown_for[name].push_back(StreamCount{stream, total});
    }
  }
  grown_.clear();
  std::vector<StepOrder> orders;
  for (auto& [name, p] : participants_) {
    if (p.dropped) continue;
    auto g = grown_for.find(name);
    if (g == grown_for.end() && p.next_due > time + 1e-9) continue;
    StepOrder order{name, step, time, {}};
    if (g != grown_for.end()) order.totals = std::move(g->second);
    for (const StreamId& stream : p.carried) {
      std::uint64_t& told = p.told[stream];
      const std::uint64_t total = totals_[stream];
      if (total <= told) continue;
      told = total;
      order.totals.push_back(StreamCount{stream, total});
    }
    p.carried.clear();
    p.waiting = true;
    orders.push_back(std::move(order));
  }
  return orders;
}

void LockstepCoordinator::Ack(const std::string& node, std::uint64_t step,
                              const std::vector<StreamCount>& published, double next_due, double wall_now) {
  auto it = participants_.find(node);
  if (it == participants_.end() || it->second.dropped || step != step_) return;
  Participant& p = it->second;
  for (const StreamCount& c : published) {
    if (c.stream.publisher != node) continue;  // a participant speaks for its own streams only
    SetTotal(c.stream, c.total);
  }
  p.next_due = next_due;
  if (p.waiting) {
    p.waiting = false;
    p.answer_wall += wall_now - step_wall_;
  }
}

std::vector<std::string> LockstepCoordinator::Pending() const {
  std::vector<std::string> names;
  for (const auto& [name, p] : participants_) {
    if (p.waiting && !p.dropped) names.push_back(name);
  }
  return names;
}

bool LockstepCoordinator::OwnCaughtUp() const {
  for (const auto& [stream, total] : totals_) {
    if (stream.publisher == options_.self || own_subscribed_.count(stream.topic) == 0) continue;
    const auto r = own_received_.find(stream);
    if (r == own_received_.end() || r->second < total) return false;
  }
  return true;
}

std::vector<std::string> LockstepCoordinator::DropLate(double wall_now) {
  std::vector<std::string> late;
  if (wall_now - step_wall_ <= options_.timeout) return late;
  for (auto& [name, p] : participants_) {
    if (p.waiting && !p.dropped) {
      p.dropped = true;
      p.waiting = false;
      p.answer_wall += wall_now - step_wall_;
      late.push_back(name);
    }
  }
  return late;
}

void LockstepCoordinator::EndStep(double wall_now) { waiting_wall_ += wall_now - step_wall_; }

std::vector<std::string> LockstepCoordinator::CountedPublishers() const {
  std::vector<std::string> names{options_.self};
  for (const auto& [name, p] : participants_) {
    if (!p.dropped) names.push_back(name);
  }
  return names;
}

std::string LockstepCoordinator::Slowest(double* seconds) const {
  std::string slowest;
  double most = -1.0;
  for (const auto& [name, p] : participants_) {
    if (p.answer_wall > most) {
      most = p.answer_wall;
      slowest = name;
    }
  }
  if (seconds) *seconds = slowest.empty() ? 0.0 : most;
  return slowest;
}

std::vector<std::pair<std::string, double>> LockstepCoordinator::AnswerTimes() const {
  std::vector<std::pair<std::string, double>> times;
  for (const auto& [name, p] : participants_) times.emplace_back(name, p.answer_wall);
  std::stable_sort(times.begin(), times.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return times;
}

std::vector<std::string> LockstepCoordinator::dropped() const {
  std::vector<std::string> names;
  for (const auto& [name, p] : participants_) {
    if (p.dropped) names.push_back(name);
  }
  return names;
}

}  // namespace world_sim
