#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "world_sim/lockstep_coordinator.h"

namespace world_sim {

// A participant's side of the lockstep protocol (lockstep_coordinator.h), without ROS. It holds
// each message of a counted stream until a step order covers it, then hands the step's messages
// on in one fixed order (streams by topic and publisher, each in the order sent) and runs the
// participant's periodic timers at the step's time. So a participant sees the same messages, in
// the same order, at the same simulated times, in every run.
class LockstepInbox {
 public:
  using Delivery = std::function<void()>;
  using TimerCallback = std::function<void(double expected, double now)>;

  // At most `capacity` messages are held; beyond that the oldest stream's messages are handed
  // on at once and counted in overflow().
  explicit LockstepInbox(std::size_t capacity = 100000) : capacity_(capacity) {}

  // A message from `stream`. Until the first order says which publishers are counted every
  // message is held; afterwards, messages of other publishers are handed on at once.
  void Arrive(const StreamId& stream, Delivery deliver);
  // The world's order for a step (the first one also names the counted publishers).
  void Order(const StepOrder& order, const std::vector<std::string>& counted_publishers);
  // An order waits and every message it covers has arrived.
  bool Ready() const;
  bool has_order() const { return has_order_; }
  std::uint64_t step() const { return order_.step; }
  double time() const { return order_.time; }
  // Runs the waiting order: hands on its messages, then the timers due by its time.
  void Run();

  // A timer firing every `period` s of simulated time from `start` (first at start + period);
  // a start of 0 (no clock yet) means from the first step's time. With `rest_until`, the timer
  // need not run before the time it returns (asked after every step it takes part in; +inf:
  // until a message comes): NextDue() tells the world so. Whenever the participant takes part
  // in a step for another reason, a timer due runs as usual.
  void AddTimer(double period, double start, TimerCallback callback, std::function<double()> rest_until = {});
  // The simulated time the next timer falls due (+inf with none).
  double NextDue() const;

  std::uint64_t overflow() const { return overflow_; }
  std::size_t held() const { return held_count_; }

 private:
  // Due times are counted in whole periods from the anchor, never summed up period by period:
  // a sum drifts off the steps' times over a long run.
  struct Timer {
    double period;
    double anchor;          // the time the timer counts from
    std::uint64_t periods;  // `due` is anchor + periods x period
    double due;
    bool anchored;          // `anchor` is known (else it is the first step's time)
    TimerCallback callback;
    std::function<double()> rest_until;
  };
  struct Stream {
    std::deque<Delivery> held;
    std::uint64_t handed = 0;  // messages handed on so far
  };

  void HandUncounted();
  void RunTimers(double now);

  std::size_t capacity_;
  std::map<StreamId, Stream> streams_;
  std::map<StreamId, std::uint64_t> allowed_;
  std::set<std::string> counted_;
  bool counted_known_ = false;
  bool has_order_ = false;
  StepOrder order_;
  std::vector<Timer> timers_;
  std::size_t held_count_ = 0;
  std::uint64_t overflow_ = 0;
};

}  // namespace world_sim
