#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace world_sim {

// The lockstep protocol (world_sim's side). In lockstep the world steps only when every
// participant (a controller, audio_propagation) has answered the step, and every message sent
// during a step is handed to its subscribers before the next one: the run is then the same
// whatever the machine's load, and as fast as the slowest participant allows.
//
// Messages are counted per stream: one node publishing on one topic (ROS keeps a stream's order).
// Participants report how many messages they have published on each stream; the world tells
// each participant, with each step, how many messages each stream it listens to holds by then,
// so the participant knows when it has them all and hands them to its callbacks in one fixed
// order. A participant takes part in a step when a timer of its falls due or a message reached
// one of its streams (but for the streams it calls passive); otherwise the world does not wait
// for it.

struct StreamId {
  std::string topic;      // resolved topic name
  std::string publisher;  // node name
  bool operator<(const StreamId& o) const {
    return topic != o.topic ? topic < o.topic : publisher < o.publisher;
  }
  bool operator==(const StreamId& o) const { return topic == o.topic && publisher == o.publisher; }
};

struct StreamCount {
  StreamId stream;
  std::uint64_t total = 0;  // messages published on the stream since the start
};

// What a participant says before the run starts (and repeats until the run has started).
struct ParticipantHello {
  std::string node;
  std::vector<std::string> subscribed;  // resolved topics whose messages it counts
  std::vector<int> connected;           // publishers its subscription to each is connected to
  std::vector<std::string> advertised;  // resolved topics it publishes and counts
  bool step_connected = false;          // its step-order subscription is connected to the world
  // Of `subscribed`, the topics whose messages do not by themselves make it take part in a step
  // (poses it only needs when it works for another reason); whenever it takes part, its order
  // covers them too.
  std::vector<std::string> passive;
};

// One step order for one participant: the step, its time, and the totals of the streams it
// listens to that grew since its last order.
struct StepOrder {
  std::string node;
  std::uint64_t step = 0;
  double time = 0.0;
  std::vector<StreamCount> totals;
};

struct LockstepOptions {
  std::string self;                       // the world's node name (publisher of its own streams)
  std::vector<std::string> participants;  // the nodes that must take part
  double timeout = 5.0;                   // wall s a participant may keep the world waiting
};

// Throws std::invalid_argument naming the field and what was expected: a timeout not above 0,
// an empty participant name or one given twice.
void ValidateOptions(const LockstepOptions& options);

class LockstepCoordinator {
 public:
  // Throws std::invalid_argument on impossible options (ValidateOptions).
  explicit LockstepCoordinator(LockstepOptions options);

  // The world's own subscriptions (topics it counts) and publications.
  void SetOwnStreams(const std::vector<std::string>& subscribed, const std::vector<std::string>& advertised);
  void OwnPublished(const std::string& topic, std::uint64_t total);
  void OwnReceived(const StreamId& stream, std::uint64_t total);

  // Registration. A hello from a node that is not a participant is ignored (returns false).
  bool Hello(const ParticipantHello& hello);
  // True when every participant still expected has said hello and is connected to every
  // known publisher of what it listens to (and the world to every participant's publishers
  // of what the world listens to). Otherwise `missing` names who is not ready yet.
  bool Ready(const std::map<std::string, int>& own_connected, std::string* missing) const;
  // Drops every participant that is not ready (after the start timeout); returns their names.
  std::vector<std::string> DropUnready(const std::map<std::string, int>& own_connected);

  // A step: the orders for the participants that take part in it (a timer due, or new
  // messages on their streams). The world then waits until Pending() is empty.
  std::vector<StepOrder> BeginStep(std::uint64_t step, double time, double wall_now);
  // A participant's answer to `step`: its publication totals and when its next timer is due.
  void Ack(const std::string& node, std::uint64_t step, const std::vector<StreamCount>& published,
           double next_due, double wall_now);
  // Participants the step still waits for, and whether the world still waits for messages
  // the participants reported publishing on streams it listens to.
  std::vector<std::string> Pending() const;
  bool OwnCaughtUp() const;
  // Drops the participants that have kept this step waiting longer than the timeout.
  std::vector<std::string> DropLate(double wall_now);
  // The world goes on to the next step: the wait since BeginStep counts as waiting time.
  void EndStep(double wall_now);
  // The nodes whose streams are counted (the world and the participants): a participant holds
  // messages from these until a step order covers them, and hands the others on at once.
  std::vector<std::string> CountedPublishers() const;

  // Summary figures.
  double waiting_wall() const { return waiting_wall_; }  // wall s spent waiting for answers
  // The participant with the longest total answer time (empty if none), and that time.
  std::string Slowest(double* seconds) const;
  // Every participant with its total answer time (wall s), longest first.
  std::vector<std::pair<std::string, double>> AnswerTimes() const;
  std::vector<std::string> dropped() const;
  bool IsParticipant(const std::string& node) const { return participants_.count(node) > 0; }

 private:
  struct Participant {
    bool said_hello = false;
    bool dropped = false;
    ParticipantHello hello;
    std::set<std::string> subscribed;
    std::set<std::string> passive;
    std::set<StreamId> carried;              // passive streams grown since its last order
    std::map<StreamId, std::uint64_t> told;  // totals sent to it so far
    double next_due = 0.0;                   // sim s of its next timer (0: the first step)
    bool waiting = false;                    // the current step waits for its answer
    double answer_wall = 0.0;                // total wall s from orders to its answers
  };

  int KnownPublishers(const std::string& topic, const std::string& except) const;
  void SetTotal(const StreamId& stream, std::uint64_t total);

  LockstepOptions options_;
  std::map<std::string, Participant> participants_;
  std::map<StreamId, std::uint64_t> totals_;
  std::set<StreamId> grown_;  // streams whose totals grew since the last step's orders
  std::map<std::string, std::set<std::string>> listeners_;  // topic -> participants counting it
  std::set<std::string> own_subscribed_, own_advertised_;
  std::map<StreamId, std::uint64_t> own_received_;
  std::uint64_t step_ = 0;
  double step_wall_ = 0.0;
  double waiting_wall_ = 0.0;
};

}  // namespace world_sim
