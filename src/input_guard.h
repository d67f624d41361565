#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

#include <boost/weak_ptr.hpp>
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/message_event.h>
#include <ros/message_traits.h>
#include <ros/ros.h>
#include <std_msgs/Header.h>

#include "subscription_stats.h"

namespace multirobot_audio {

// Checks and counts what a node receives, input by input and publisher by publisher, so that no
// message goes unaccounted for. Each message that arrives is
//   accepted  handed to the node,
//   rejected  it failed a check: the message's own (a non-finite number, a wrong size; see
//             input_checks.h), or its stamp is older than the last one accepted from the same
//             connection, or the node's (a job count going backwards), or
//   dropped   lost on the way: to a full queue of the node's own, or before the callback. roscpp's
//             subscription queue drops its oldest message when full and says so nowhere usable,
//             so for a message with a header (every input but cmd_vel) the guard counts the
//             gaps in header.seq, which the publisher's roscpp (or rospy) numbers one by one
//             per topic: exact per publisher connection, also for what the publisher's own
//             queue lost, and seen when the publisher's next message arrives. For a message
//             without one (cmd_vel, and the topics actionlib subscribes: see Watch) it takes
//             roscpp's own drop counter of the connection (SubscriptionStats), which roscpp
//             reports for one connection per topic only: exact with one publisher.
// The counts go out on /diagnostics (the task "inputs", once a wall second) and into the node's
// exit summary; rejections and drops are logged, throttled per input, naming the publisher, the
// field and the value. Thread-safe.
class InputGuard {
 public:
  // What a node's callback made of a message that passed the checks.
  struct Verdict {
    enum class Kind { kAccepted, kRejected, kDropped };
    Kind kind = Kind::kAccepted;
    std::string reason;
    static Verdict Accept() { return {}; }
    static Verdict Reject(std::string why) { return {Kind::kRejected, std::move(why)}; }
    static Verdict Drop(std::string why) { return {Kind::kDropped, std::move(why)}; }
  };
  // What is wrong with a message, naming the field and value; empty when nothing is.
  template <class M>
  using Check = std::function<std::string(const M&)>;

  // Publishes through a diagnostic updater of its own.
  InputGuard();
  // Adds its task to the node's `updater`, which the node updates itself.
  explicit InputGuard(diagnostic_updater::Updater& updater);
  InputGuard(const InputGuard&) = delete;
  InputGuard& operator=(const InputGuard&) = delete;

  // The callback to subscribe to `topic` (a resolved name) with: it runs `check` and, for a
  // message with a header, books its seq and checks its stamp's order, then hands the message to
  // `use`, which returns nothing (accepted) or a Verdict.
  template <class M, class Use>
  std::function<void(const ros::MessageEvent<M const>&)> Checked(const std::string& topic, Check<M> check, Use use);

  // Subscribes to `topic` (relative to `nh`) with Checked(): straight through roscpp, or through
  // `via` (a LockstepParticipant: anything with its SubscribeEvents).
  template <class M, class Use>
  ros::Subscriber Subscribe(ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue, Check<M> check, Use use) {
    return nh.subscribe<M>(topic, queue,
                           boost::function<void(const ros::MessageEvent<M const>&)>(
                               Checked<M>(nh.resolveName(topic), std::move(check), std::move(use))));
  }
  template <class M, class Via, class Use>
  ros::Subscriber Subscribe(Via& via, ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue,
                            Check<M> check, Use use) {
    return via.template SubscribeEvents<M>(nh, topic, queue,
                                           Checked<M>(nh.resolveName(topic), std::move(check), std::move(use)));
  }

  // A subscription the node does not handle itself (actionlib's): only roscpp's counts; what
  // roscpp hands on to the library counts as accepted.
  void Watch(const std::string& topic);

  void Diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  // "inputs accepted A, rejected R, dropped D", and per input with any rejected or dropped.
  std::string Summary();

 private:
  struct FromPublisher {
    std::uint64_t accepted = 0, rejected = 0;
    std::uint64_t dropped = 0;  // by the node itself, and (numbered inputs) the gaps in seq
    // The connection the figures below are of (roscpp's header of it): a new one (the publisher
    // restarted or reconnected) starts afresh.
    boost::weak_ptr<ros::M_string> connection;
    std::uint32_t last_seq = 0;
    ros::Time last_stamp;  // of the last message accepted
    bool has_seq = false, has_stamp = false;
  };
  struct Input {
    std::string topic;
    bool numbered = false;  // its messages have a header: drops from seq, not from roscpp
    bool watched = false;
    std::map<std::string, FromPublisher> publishers;
    std::string last_problem;
    ros::WallTime last_warning;
    std::uint64_t reported_drops = 0;  // queue drops already said in the log
  };
  // One publisher's figures with roscpp's (queued: only in an input's total, see Sum()).
  struct Row {
    std::uint64_t received = 0, accepted = 0, rejected = 0, dropped = 0, queued = 0;
  };

  void Start();
  bool UsesStats() const;  // some input takes its drops from roscpp (with mutex_ held)
  void SampleStats();      // reads roscpp's counts if so
  std::size_t AddInput(const std::string& topic, bool numbered, bool watched);
  FromPublisher& Publisher(Input& input, const std::string& name);
  // Books the arrival of a message with `header` from `publisher` over `connection`: counts the
  // messages its seq says were lost since the last one and, when `check_stamp`, returns what is
  // wrong with its stamp: older than the last accepted from the same connection ("" if nothing;
  // the stamp is then remembered).
  std::string Arrive(std::size_t input, const std::string& publisher,
                     const boost::shared_ptr<ros::M_string>& connection, const std_msgs::Header& header,
                     bool check_stamp);
  void CountLocked(Input& input, const std::string& publisher, const Verdict& verdict);
  std::map<std::string, Row> Rows(const Input& input) const;
  static Row Sum(const std::map<std::string, Row>& rows);

  std::mutex mutex_;
  std::string node_;
  std::vector<Input> inputs_;
  SubscriptionStats stats_;
  std::unique_ptr<diagnostic_updater::Updater> own_updater_;
  ros::WallTimer sample_timer_, diagnostics_timer_;
};

template <class M, class Use>
std::function<void(const ros::MessageEvent<M const>&)> InputGuard::Checked(const std::string& topic, Check<M> check,
                                                                         Use use) {
  constexpr bool numbered = ros::message_traits::HasHeader<M>::value;
  const std::size_t index = AddInput(topic, numbered, false);
  return [this, index, check, use](const ros::MessageEvent<M const>& event) {
    const boost::shared_ptr<M const>& msg = event.getConstMessage();
    const std::string& publisher = event.getPublisherName();
    std::string problem = check ? check(*msg) : std::string();
    if constexpr (numbered) {
      const std::string late = Arrive(index, publisher, event.getConnectionHeaderPtr(),
                                      *ros::message_traits::header(*msg), problem.empty());
      if (problem.empty()) problem = late;
    }
    Verdict verdict = Verdict::Reject(problem);
    if (problem.empty()) {
      if constexpr (std::is_void_v<std::invoke_result_t<Use, const boost::shared_ptr<M const>&>>) {
        use(msg);
        verdict = Verdict::Accept();
      } else {
        verdict = use(msg);
      }
    }
    std::lock_guard<std::mutex> lock(mutex_);
    CountLocked(inputs_[index], publisher, verdict);
  };
}

}  // namespace multirobot_audio
