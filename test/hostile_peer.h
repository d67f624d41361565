#pragma once

// A broken peer for the hostile-input rostests: it feeds nodes' inputs with garbage and floods,
// counts what it sent, and reads back what each node's InputGuard reports on /diagnostics.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/message_traits.h>
#include <ros/ros.h>

namespace multirobot_audio::testing {

// One input's figures as an InputGuard reports them (input_guard.h); queued only in totals.
struct InputFigures {
  bool found = false;
  std::uint64_t accepted = 0, rejected = 0, dropped = 0, received = 0, queued = 0;
  std::uint64_t settled() const { return accepted + rejected + dropped; }
};

// The latest status of every node on /diagnostics.
class DiagnosticsWatch {
 public:
  explicit DiagnosticsWatch(ros::NodeHandle nh);
  // `node`'s figures for `topic` (resolved), from `publisher` ("": from all publishers).
  InputFigures Figures(const std::string& node, const std::string& topic, const std::string& publisher = "") const;
  // The value of `key` in the status `name` (e.g. "audio_propagation: poses"); "" when none.
  std::string Value(const std::string& name, const std::string& key) const;
  // The message of the status `name`; "" when none.
  std::string Message(const std::string& name) const;
  // The level of the status `name`; -1 when it was never seen.
  int Level(const std::string& name) const;
  // Wall s since the status `name` last came; +inf when never.
  double Age(const std::string& name) const;

 private:
  void OnDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg);

  ros::Subscriber sub_;
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> latest_;
  std::map<std::string, ros::WallTime> seen_;
};

// One input of one node, fed by the peer: a publisher and the variants it cycles through, each
// good (the node must accept it) or bad (the node must reject it).
class Feed {
 public:
  Feed(std::string node, std::string topic) : node_(std::move(node)), topic_(std::move(topic)) {}
  virtual ~Feed() = default;
  const std::string& node() const { return node_; }
  const std::string& topic() const { return topic_; }
  std::size_t variants() const { return good_.size(); }
  bool good(std::size_t variant) const { return good_[variant]; }
  virtual bool Connected() const = 0;
  // Publishes variant `variant`; the stamp of a message with a header is the ROS time now,
  // or for a "backwards" variant half a second before the last good one sent.
  void Send(std::size_t variant) {
    Publish(variant);
    ++sent_;
    (good_[variant] ? good_sent_ : bad_sent_)++;
  }
  std::uint64_t sent() const { return sent_; }
  std::uint64_t good_sent() const { return good_sent_; }
  std::uint64_t bad_sent() const { return bad_sent_; }

 protected:
  virtual void Publish(std::size_t variant) = 0;
  std::vector<bool> good_;

 private:
  std::string node_, topic_;
  std::uint64_t sent_ = 0, good_sent_ = 0, bad_sent_ = 0;
};

template <class M>
class TypedFeed : public Feed {
 public:
  using Change = std::function<void(M&)>;
  // Feeds `topic` (resolved) of the node named `node` (as its diagnostics name it, e.g.
  // "robot_0/wanderer"); `valid` is a message the node must accept.
  TypedFeed(ros::NodeHandle& nh, const std::string& node, const std::string& topic, M valid)
      : Feed(node, topic), valid_(std::move(valid)) {
    // Never full: every message the test counts as sent must reach the node's connection.
    pub_ = nh.advertise<M>(topic, 1000000);
  }
  TypedFeed& Good(Change change = {}) { return Add(true, false, std::move(change)); }
  TypedFeed& Bad(Change spoil) { return Add(false, false, std::move(spoil)); }
  // A valid message stamped before the last good one (messages with a header only).
  TypedFeed& Backwards() { return Add(false, true, {}); }
  bool Connected() const override { return pub_.getNumSubscribers() > 0; }

 protected:
  void Publish(std::size_t variant) override {
    M msg = valid_;
    if (changes_[variant]) changes_[variant](msg);
    if constexpr (ros::message_traits::HasHeader<M>::value) {
      ros::Time now = ros::Time::now();
      if (backwards_[variant]) {
        now = last_good_ > ros::Time(0.5) ? last_good_ - ros::Duration(0.5) : ros::Time(0, 1);
      } else if (good_[variant]) {
        last_good_ = now;
      }
      ros::message_traits::header(msg)->stamp = now;
    }
    pub_.publish(msg);
  }

 private:
  TypedFeed& Add(bool good, bool backwards, Change change) {
    good_.push_back(good);
    backwards_.push_back(backwards);
    changes_.push_back(std::move(change));
    return *this;
  }

  ros::Publisher pub_;
  M valid_;
  std::vector<bool> backwards_;
  std::vector<Change> changes_;
  ros::Time last_good_;
};

// Sends every variant of every feed once (good ones first, a few ms apart, so no queue fills).
void SendEachOnce(const std::vector<Feed*>& feeds);

// Cycles every feed through its variants at `rate` Hz each for `seconds` of wall time (as fast
// as the machine allows when it cannot keep up); returns the rate each feed reached, in Hz.
std::vector<double> Flood(const std::vector<Feed*>& feeds, double rate, double seconds);

// One good message on each feed (the first variant): a node counts the messages lost before a
// numbered message (one with a header) when the publisher's next one arrives.
void SendClosing(const std::vector<Feed*>& feeds);

// Waits until each node reports every message of `feeds` from this node as accepted, rejected
// or dropped (and nothing of the input still queued), or `wall_seconds` pass; then checks that,
// and with `exact`, where nothing was dropped, that each good message was accepted and each bad
// one rejected. Prints a line per feed.
void ExpectAccounted(const DiagnosticsWatch& watch, const std::vector<Feed*>& feeds, bool exact,
                     double wall_seconds);

}  // namespace multirobot_audio::testing
