#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "local_mutex/message.h"
#include "local_mutex/mutex_options.h"

namespace local_mutex {

// The states of the thesis's Figure 7.2. SILENT is a deferred WANTED: the robot still wants
// the lock but has heard a request with priority over its own and keeps quiet.
enum class State : std::uint8_t { kReleased = 0, kWanted = 1, kSilent = 2, kHeld = 3 };
const char* StateName(State s);

// What the lock did or heard, for logs, timelines and the ROS node's counters.
struct MutexEvent {
  enum class Kind {
    kStateChange,  // `state` is the new state
    kSent,         // `message` was handed to the audio link
    kHeard,        // `message` arrived from another robot
    kNoise,        // noise or a corrupted packet
    kMalformed,    // a packet that is not ours (wrong length, unknown type): treated as noise
    kDuplicateId,  // a packet with our id that we did not send: treated as noise
    kEcho,         // our own packet heard back shortly after sending it: ignored
  };
  Kind kind = Kind::kStateChange;
  double time = 0.0;
  State state = State::kReleased;  // after the event
  LamportTime clock = 0;           // after the event
  Message message;                 // for kSent, kHeard, kDuplicateId, kEcho
};
const char* EventKindName(MutexEvent::Kind k);

struct MutexCounters {
  std::uint64_t sent = 0, heard = 0, noise = 0, malformed = 0, duplicate_ids = 0, echoes = 0, grants = 0;
};

// Audio-based local mutual exclusion: the thesis's Programs 7.1 and 7.2.
//
// The caller owns time and the audio link: it passes the time (s, any monotonic origin) to
// every call, calls Tick() often (10 Hz is plenty against timers of seconds), hands over what
// the link heard, and sends what `send` is given. Nothing here blocks or sleeps.
//
// The rules, and where the pseudo-code left a choice:
// - The Lamport clock starts at 0 and is incremented for every message sent and every noise
//   heard; a packet heard sets it to 1 + max(clock, stamp). A message carries the clock as it
//   was before the send's own increment; a REQUEST always carries T_i, the clock when the
//   robot entered WANTED, so repeats of one request compare equal.
// - WANTED: the grab timer (t_grab) restarts on every sound heard, packet or noise; requests go
//   out every t_request (Gaussian), the first one t_request after entering WANTED; the grab
//   timer running out means t_grab of silence: HELD.
// - Entering WANTED, the robot first looks at what it heard recently (section 6.3.1; Program
//   7.2 forgets it): a REQUEST heard in the last t_grab has priority over ours (our clock has
//   passed its time), so we start SILENT, deferring as if it had just arrived when it did.
//   Without this, a robot that heard a request just before wanting the lock asks anyway, and if
//   that one request collides, both robots take the lock (seen in the random trials).
// - A LOCK heard while WANTED or SILENT brings the next request forward to at most a fresh
//   t_request from now (SCHEDULEREQUEST): the holder is no competitor, and our request must be
//   on the air when it lets go. This also shortens a silence, as the program does.
// - A REQUEST heard whose (T_j, j) precedes our (T_i, i) sends us to SILENT (POSTPONEREQUEST):
//   no request for t_grab + t_request, and the grab timer set to t_grab after that next
//   request. Program 7.2 would let a later noise reset the grab timer to plain t_grab and so
//   possibly take the lock in silence without ever asking; the text of section 7.1 says the
//   timer runs until t_grab after the first request is sent, so while SILENT a sound restarts
//   it to no earlier than that.
// - SILENT ends when its transmit timer runs out: the request is sent and the robot is WANTED.
// - HELD: a LOCK at once on taking the lock (Figure 7.2's entry action), then every t_lock
//   (Gaussian). Program 7.2 read literally waits t_lock before the first announcement, which
//   leaves a robot whose requests were lost in a collision t_lock to take the lock too; the
//   random trials showed exactly that. Nothing heard changes HELD.
// - RELEASED: silent; packets and noise only move the clock.
// - A packet that is not a lock message (wrong length, unknown type) is noise, as the thesis
//   treats anything it cannot read. A packet with our own id repeating what we sent within
//   echo_window is our echo and ignored; any other packet with our id means a second robot has
//   our id: counted, reported, and treated as noise (it delays us, which is the safe side).
// - Intervals drawn from the Gaussians are clamped to at least a tenth of their mean.
class LocalMutex {
 public:
  using Send = std::function<void(const std::vector<std::uint8_t>& packet)>;
  // Returns a draw from N(mean, sd); injectable so tests can script the intervals.
  using Gaussian = std::function<double(double mean, double sd)>;
  using Observer = std::function<void(const MutexEvent& event)>;

  // Throws std::invalid_argument for impossible options (see ValidateMutexOptions). Without a
  // `gaussian`, intervals come from a generator seeded with options.seed.
  LocalMutex(const MutexOptions& options, Send send, Gaussian gaussian = {});

  void SetObserver(Observer observer) { observer_ = std::move(observer); }

  // RELEASED -> WANTED (REQUESTLOCK); false, and nothing changes, in any other state.
  bool Request(double now);
  // Any state -> RELEASED: lets go of a held lock or withdraws a request; false (a no-op) when
  // already RELEASED.
  bool Release(double now);

  // What the audio link heard.
  void HearPacket(const std::vector<std::uint8_t>& packet, double now);
  void HearNoise(double now);

  // Runs the timers up to `now`: takes the lock, sends requests and announcements.
  void Tick(double now);

  State state() const { return state_; }
  LamportTime clock() const { return clock_; }
  int robot_id() const { return options_.robot_id; }
  const MutexOptions& options() const { return options_; }
  // (T_i, i) of the current request; meaningful while WANTED, SILENT or HELD.
  RequestTuple request() const { return {request_time_, static_cast<std::uint8_t>(options_.robot_id)}; }
  double grab_deadline() const { return grab_deadline_; }
  double next_transmit() const { return next_transmit_; }
  // When the current state was entered.
  double state_since() const { return state_since_; }
  const MutexCounters& counters() const { return counters_; }

 private:
  void Enter(State s, double now);
  void Transmit(MessageType type, LamportTime stamp, double now);
  void PostponeGrab(double now);
  void OnSound(double now);  // what any sound does while WANTED or SILENT
  void Notify(MutexEvent::Kind kind, double now, const Message& m = {});
  double Draw(double mean, double sd);

  MutexOptions options_;
  Send send_;
  Gaussian gaussian_;
  Observer observer_;
  std::mt19937 rng_;

  State state_ = State::kReleased;
  LamportTime clock_ = 0;
  LamportTime request_time_ = 0;
  double grab_deadline_ = 0.0, next_transmit_ = 0.0, state_since_ = 0.0;
  Message last_sent_;
  double last_sent_at_ = -1e300;
  RequestTuple last_request_heard_;
  double last_request_heard_at_ = -1e300;
  MutexCounters counters_;
};

}  // namespace local_mutex
