#pragma once

// Two-way acoustic ranging from a team's ordinary packets (BeepBeep, SenSys 2007), with no
// synchronised clocks and no extra packets. Every robot times, on its own sound card's capture
// clock, the first arrival of each packet it hears, its own included (its microphone hears its
// speaker). For robots A and B, A's packet heard by A at a1 and by B at b1, and B's packet heard
// by B at b2 and by A at a2:
//
//   range = c/2 ((a2 - a1) - (b2 - b1) / (1 + rho)) + offset
//
// whatever either sound card's latency: each clock's unknown offset cancels within its own
// difference. rho is B's clock over A's minus 1 (the rate error A's receiver measures on B's
// packets): B's interval is told in A's seconds before the two are compared. `offset` holds what
// does not cancel: each robot's own speaker-to-microphone delay, found by calibration.
//
// The robots share their timings over a side channel (ROS); a TwoWayRanger on robot A takes
// every timing it is given, pairs exchanges with each teammate within a window, and keeps a
// filtered range per teammate: the median of its latest samples, with an uncertainty. No ROS.
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ranging {

struct RangerOptions {
  double speed_of_sound = 343.0;  // m/s
  // The two packets of an exchange at most this far apart (s, on this robot's clock): the
  // rate correction's error grows with the interval, and the robots move.
  double pair_window = 20.0;
  // A teammate's clock further than this from ours (fraction) is a bad report: sound cards are
  // within a few hundred ppm, and a modem's own limit is wider than any real card.
  double max_rate_error = 0.002;
  int samples = 5;          // range samples per teammate the estimate is the median of
  double max_age = 60.0;    // s: older samples are dropped
  double max_range = 200.0;  // m: a sample beyond it (or below -1 m) is a mispairing, skipped
  double offset = 0.0;      // m added to every sample (calibration of the fixed delays)
  // One sample's uncertainty (m, one standard deviation): the least a range is told with.
  double sample_std = 0.03;
};

// Throws std::invalid_argument naming the field, its value and what was expected: a speed of
// sound not in 100..2000 m/s, a window or maximum age not above 0, a rate error not in 0..0.05,
// fewer than 1 sample, a maximum range or sample_std not above 0, an offset beyond 10 m, anything
// not finite.
void ValidateRangerOptions(const RangerOptions& options);

// One packet timed by one robot's microphone.
struct Timing {
  std::string sender;              // who sent the packet
  std::string listener;            // whose microphone timed it (the sender itself for its own)
  std::vector<std::uint8_t> data;  // the packet's payload: what tells packets apart
  double arrival = 0.0;            // s on the listener's capture clock (first arrival)
  // The sender's clock over the listener's, minus 1, as the listener's receiver measured it;
  // 0 for a robot's own packet.
  double rate_error = 0.0;
  // The listener's clock's life: it goes up when the clock restarts (a sound card reopened after
  // a failure), and the listener's earlier timings then pair with nothing new.
  std::uint32_t clock_epoch = 0;
  // When the listener heard it by its system clock (s; the team's clocks agree to well within
  // kSamePacketS, as machines on one ROS master do): what tells two sendings of one payload
  // apart. NaN: unknown, and one payload is then one packet within the window.
  double stamp = std::numeric_limits<double>::quiet_NaN();
};

// Timings of one sender's payload whose stamps are this close are of one sending of it.
constexpr double kSamePacketS = 1.0;

// A sender's word that it is sending a payload (before any timing of it): a timing with NaN
// arrival and listener == sender. It tells receptions of that payload whose they are.
inline bool IsAnnouncement(const Timing& t) { return t.sender == t.listener && t.arrival != t.arrival; }

// A teammate's range as this robot knows it.
struct Range {
  std::string teammate;
  double range = 0.0;      // m
  double range_std = 0.0;  // m, one standard deviation
  double age = 0.0;        // s since its latest sample (this robot's clock)
  int samples = 0;         // behind the estimate
};

// Timings refused, by reason (each counted, never turned into a range).
struct Refused {
  std::uint64_t unknown_robot = 0;     // a sender or listener not in the team
  std::uint64_t backwards = 0;         // a listener's clock earlier than its last timing's (or an older
                                       // epoch), or not finite
  std::uint64_t bad_rate = 0;          // a rate error beyond max_rate_error, or not finite
  std::uint64_t repeated_payload = 0;  // one listener timing one sending twice (or, without stamps,
                                       // one sender's payload twice within the window)
  std::uint64_t implausible = 0;       // a pairing whose range is beyond max_range
  std::uint64_t total() const { return unknown_robot + backwards + bad_rate + repeated_payload + implausible; }
};

class TwoWayRanger {
 public:
  // `self` is this robot; `team` every robot's name (this one's may be among them); an empty team
  // takes any robot's timings. Throws std::invalid_argument for impossible options or an empty
  // self.
  TwoWayRanger(std::string self, std::vector<std::string> team, const RangerOptions& options);

  // A timing by any robot of the team (this one's own included), in each listener's order; or an
  // announcement (IsAnnouncement).
  void Add(const Timing& timing);
  // Who sent the latest packet carrying `data` within the window, if one robot did (an
  // announcement or a timing of its own); none if no one or several did.
  std::optional<std::string> SenderOf(const std::vector<std::uint8_t>& data) const;
  // Every teammate with a range, by name; `now` is this robot's clock (for ages and expiry).
  std::vector<Range> Ranges(double now) const;
  std::optional<Range> RangeTo(const std::string& teammate, double now) const;
  const Refused& refused() const { return refused_; }
  // This robot's own clock over true seconds, minus 1 (its sound card's rate, tracked against
  // the system clock): the round trip it measures is told in true seconds. Left at 0, a card
  // 100 ppm off makes every range 100 ppm long (a millimetre at 10 m).
  void SetOwnRateError(double rate_error) { own_rate_error_ = rate_error; }

 private:
  // One packet: its sender's own timing and the others' (listener -> arrival, rate error).
  struct Packet {
    std::string sender;
    std::vector<std::uint8_t> data;
    std::map<std::string, Timing> heard;
    bool repeated = false;
    double announced = 0.0;  // this robot's clock when the sender announced it (0: never)
  };
  void Pair(const Packet& packet, const std::string& teammate);
  double RateOf(const std::string& teammate) const;
  void Forget();
  // The sending of `data` by `sender` that a timing stamped `stamp` belongs to: the latest whose
  // timings are within kSamePacketS of it (or, with no stamp on either side, the latest).
  Packet* Find(const std::string& sender, const std::vector<std::uint8_t>& data, double stamp);
  Packet& NewPacket(const std::string& sender, const std::vector<std::uint8_t>& data);
  double latest_announcement_ = 0.0;  // announcements so far

  std::string self_;
  std::vector<std::string> team_;
  RangerOptions options_;
  std::vector<Packet> packets_;  // within the window, oldest first
  std::map<std::string, double> last_arrival_;  // per listener
  std::map<std::string, std::uint32_t> epoch_;    // per listener
  void Restart(const std::string& listener);
  std::map<std::string, std::vector<double>> rates_;  // per teammate: its latest rate errors heard here
  struct Sampled {
    double range, at;
  };
  std::map<std::string, std::vector<Sampled>> samples_;
  double own_rate_error_ = 0.0;
  Refused refused_;
};

}  // namespace ranging
