// Sound-card faults over the air through ALSA (test/nava_air_faults.test, run by
// test/nava_air.sh): robot_0's process is stalled long enough for its streams to over- and
// underrun, then the PulseAudio server that is everyone's sound card is killed in the middle of
// one of robot_0's packets and started again. Every packet must be heard exactly once.
#include <signal.h>
#include <sys/types.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/CarrierSense.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include "wait_for.h"

namespace multirobot_audio {
namespace {

using testing::WaitFor;
const std::vector<std::string> kLinks = {"robot_0", "robot_1", "robot_2"};
const std::vector<std::string> kListeners = {"robot_1", "robot_2"};
// Packets robot_0 is asked to send at once: more than its queue empties before the failure.
constexpr int kPackets = 14;
constexpr double kServerDownSeconds = 2.0;

// Packet k of round r of the restart test.
std::vector<std::uint8_t> Numbered(int k, int r) { return {0x60, static_cast<std::uint8_t>(k), static_cast<std::uint8_t>(r), 0xA5}; }

// What the test hears of the three links: receptions, carrier, diagnostics and error lines.
class Links {
 public:
  Links() {
    tx_ = nh_.advertise<AudioPacket>("robot_0/audio/tx", 50);
    for (const std::string& name : kLinks) {
      subs_.push_back(nh_.subscribe<AudioReception>(name + "/audio/rx", 200,
                                                    [this, name](const AudioReception::ConstPtr& m) { heard_[name].push_back(*m); }));
      subs_.push_back(nh_.subscribe<CarrierSense>(name + "/audio/carrier", 200, [this, name](const CarrierSense::ConstPtr& m) {
        rises_[name] += m->carrier && !carrier_[name];
        carrier_[name] = m->carrier;
      }));
    }
    subs_.push_back(nh_.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 100, [this](const auto& m) { OnDiagnostics(*m); }));
    subs_.push_back(nh_.subscribe<rosgraph_msgs::Log>("/rosout", 1000, [this](const rosgraph_msgs::Log::ConstPtr& m) {
      if (m->level >= rosgraph_msgs::Log::ERROR) errors_logged_[m->name].push_back(m->msg);
    }));
  }
  // Every link publishes its carrier and diagnostics, robot_0 listens to the test, and all have
  // calibrated.
  bool Ready() {
    const bool up = WaitFor([&] { return carrier_.size() == kLinks.size() && status_.size() == kLinks.size() &&
                                         tx_.getNumSubscribers() > 0; }, 30.0);
    ros::WallDuration(2.0).sleep();
    ros::spinOnce();
    return up;
  }
  void Send(std::vector<std::uint8_t> data) {
    AudioPacket p;
    p.header.stamp = ros::Time::now();
    p.data = std::move(data);
    tx_.publish(p);
  }
  void Forget() {
    heard_.clear();
    errors_seen_.clear();
  }
  // How often `link` heard each of round `round`'s numbered packets, by number.
  std::map<int, int> Numbers(const std::string& link, int round) {
    std::map<int, int> out;
    for (const AudioReception& r : heard_[link]) {
      if (r.kind == AudioReception::PACKET && r.data.size() == 4 && r.data[0] == 0x60 && r.data[2] == round) ++out[r.data[1]];
    }
    return out;
  }
  int Packets(const std::string& link, const std::vector<std::uint8_t>& data) {
    int n = 0;
    for (const AudioReception& r : heard_[link]) n += r.kind == AudioReception::PACKET && r.data == data;
    return n;
  }
  int Receptions(const std::string& link) { return static_cast<int>(heard_[link].size()); }
  // Whether `link` heard packet k of round `round` garbled by the air after the fault was dealt
  // with: it missed k, heard packets k-1 and k+1 (unless k is the last), and a garbled packet
  // (BAD_CRC noise) between them, after `restarted` (for the last, within 2 s of k-1). When k-1
  // was heard before the restart, k is the packet the fault cut, sent again as the first after
  // the reopen, when the server garbles most (the cut copy's own BAD_CRC, before the restart,
  // does not count).
  bool GarbledLater(const std::string& link, int k, int round, const ros::Time& restarted) {
    if (Numbers(link, round).count(k)) return false;
    ros::Time before, after;
    for (const AudioReception& r : heard_[link]) {
      if (r.kind != AudioReception::PACKET || r.data.size() != 4 || r.data[0] != 0x60 || r.data[2] != round) continue;
      if (r.data[1] == k - 1) before = r.header.stamp;
      if (r.data[1] == k + 1) after = r.header.stamp;
    }
    if ((before.isZero() && k > 1) || (k < kPackets && after.isZero())) return false;
    if (before < restarted) before = restarted;
    // (A packet and the gap after it last about 1 s: the last one's garbling ends within 2 s.)
    const ros::Time until = after.isZero() ? before + ros::Duration(2.0) : after;
    for (const AudioReception& r : heard_[link]) {
      if (r.kind == AudioReception::NOISE && r.noise == AudioReception::BAD_CRC && r.header.stamp > before &&
          r.header.stamp < until) {
        return true;
      }
    }
    return false;
  }
  int rises(const std::string& link) { return rises_[link]; }
  // A link's latest diagnostics value ("" when it has none).
  std::string Value(const std::string& link, const std::string& key) {
    for (const auto& kv : status_[link].values) {
      if (kv.key == key) return kv.value;
    }
    return "";
  }
  double Number(const std::string& link, const std::string& key) {
    const std::string v = Value(link, key);
    return v.empty() ? -1.0 : std::atof(v.c_str());
  }
  bool ErrorSeen(const std::string& link) { return errors_seen_.count(link) > 0; }
  bool LoggedError(const std::string& node, const std::string& text) {
    for (const std::string& m : errors_logged_[node]) {
      if (m.find(text) != std::string::npos) return true;
    }
    return false;
  }
  // What a link heard, for failure messages.
  std::string Describe(const std::string& link) {
    std::string out;
    for (const AudioReception& r : heard_[link]) {
      char line[128];
      std::snprintf(line, sizeof line, "\n  %.3f %s noise %d [0]=%d [1]=%d", r.header.stamp.toSec(),
                    r.kind == AudioReception::PACKET ? "packet" : "noise", r.noise, r.data.empty() ? -1 : r.data[0],
                    r.data.size() < 2 ? -1 : r.data[1]);
      out += line;
    }
    return out;
  }

 private:
  void OnDiagnostics(const diagnostic_msgs::DiagnosticArray& array) {
    for (const auto& s : array.status) {
      for (const std::string& link : kLinks) {
        if (s.name.find(link + "/nava_modem") == std::string::npos) continue;
        status_[link] = s;
        if (s.level == diagnostic_msgs::DiagnosticStatus::ERROR) errors_seen_.insert(link);
      }
    }
  }

  ros::NodeHandle nh_;
  ros::Publisher tx_;
  std::vector<ros::Subscriber> subs_;
  std::map<std::string, std::vector<AudioReception>> heard_;
  std::map<std::string, bool> carrier_;
  std::map<std::string, int> rises_;
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> status_;
  std::set<std::string> errors_seen_;
  std::map<std::string, std::vector<std::string>> errors_logged_;  // by node name
};

Links* links = nullptr;

// The PID of a running node, from its own XML-RPC server (as rosnode does); -1 if unknown.
int NodePid(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, uri;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, uri, true)) return -1;
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(uri), host, port)) return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue pid_args, answer;
  pid_args[0] = ros::this_node::getName();
  if (!client.execute("getPid", pid_args, answer) || answer.getType() != XmlRpc::XmlRpcValue::TypeArray || answer.size() < 3) {
    return -1;
  }
  return static_cast<int>(answer[2]);
}

// Each link's reopens so far (-1 before its first diagnostics).
std::map<std::string, double> Reopens() {
  std::map<std::string, double> out;
  for (const std::string& link : kLinks) out[link] = links->Number(link, "device reopens");
  return out;
}

// Runs test/nava_air.sh's control of the air: "kill" or "start".
bool Air(const std::string& action) {
  const char* control = std::getenv("NAVA_AIR_CONTROL");
  if (!control) return false;
  return std::system((std::string(control) + " " + action).c_str()) == 0;
}

// robot_0 stops for half a second (SIGSTOP, then SIGCONT): PulseAudio keeps what it captured
// meanwhile (a sound server's capture does not overrun), so it falls half a second behind. It
// must count that (capture catch-ups) and catch up: its own packet's echo then still falls
// within its deaf time (a link that stayed behind would hear the echo's last half as busy
// air), and the listeners hear its packet. Its playback runs dry too, but whether ALSA's pulse
// plugin reports that underrun depends on how much the sound server had buffered: on a busy
// machine the 0.5 s stall was absorbed (catch-ups 0 -> 1, underruns 0 -> 0), so underruns are
// only printed here; the link's counting of underruns the device reports is nava_link_test's
// (UnderrunningDevice).
TEST(NavaAirFaults, AStalledLinkCountsItsXrunsAndCatchesUp) {
  ASSERT_TRUE(links->Ready()) << "the nava_modem nodes did not come up";
  const double catch_ups = links->Number("robot_0", "capture catch-ups");
  const double underruns = links->Number("robot_0", "playback underruns");
  ASSERT_GE(catch_ups, 0.0) << "no diagnostics from robot_0";
  const int pid = NodePid("/robot_0/nava_modem");
  ASSERT_GT(pid, 0) << "robot_0's nava_modem has no PID";
  ASSERT_EQ(kill(pid, SIGSTOP), 0);
  ros::WallDuration(0.5).sleep();
  ASSERT_EQ(kill(pid, SIGCONT), 0);
  EXPECT_TRUE(WaitFor([&] { return links->Number("robot_0", "capture catch-ups") > catch_ups; }, 5.0))
      << "capture catch-ups " << catch_ups << " -> " << links->Value("robot_0", "capture catch-ups");
  std::cout << "stall: playback underruns " << underruns << " -> " << links->Value("robot_0", "playback underruns") << "\n";
  // The air is real time on a shared machine: a packet garbled by some other stall may be
  // tried again, up to three tries; robot_0 hearing itself fails at once.
  std::string failures;
  for (std::uint8_t attempt = 1; attempt <= 3; ++attempt) {
    ros::WallDuration(1.0).sleep();
    links->Forget();
    const std::vector<std::uint8_t> data = {0x50, attempt, 0x02, 0x03};
    links->Send(data);
    std::string missed;
    for (const std::string& listener : kListeners) {
      if (!WaitFor([&] { return links->Packets(listener, data) > 0; }, 5.0)) {
        missed += "\n" + listener + " did not hear robot_0; it heard:" + links->Describe(listener);
      }
    }
    ros::WallDuration(1.0).sleep();
    ros::spinOnce();
    ASSERT_EQ(links->Receptions("robot_0"), 0) << "robot_0 heard its own packet:" << links->Describe("robot_0");
    if (missed.empty()) {
      if (!failures.empty()) std::fprintf(stderr, "nava_air_faults_rostest: heard on try %d after:%s\n", attempt, failures.c_str());
      return;
    }
    failures += "\ntry " + std::to_string(attempt) + ":" + missed;
  }
  ADD_FAILURE() << "robot_0's packet was not heard on any of three tries:" << failures;
}

// robot_0 is asked for kPackets numbered packets at once. Once the listeners have heard a few,
// the sound server is killed about 0.15 s into the next packet (robot_1's carrier rising marks
// its start) and started again kServerDownSeconds later. Every link reports the failure (an
// error line, diagnostics at ERROR while down) and reopens, robot_0 sends the cut packet again,
// and each listener hears every packet exactly once.
//
// The shared server is everyone's air and everyone's sound card at once, which real robots'
// are not: killing it also loses what the listeners had not yet read of sound robot_0 had
// already played whole. On a starved machine the carrier's message, the test's wake-up and the
// kill lag by more than the rest of a packet (CI once killed the server 0.4 s into a 0.37 s
// packet: robot_0 had played it whole and rightly re-queued nothing, and the listeners lost its
// end). A round whose kill missed robot_0's packet (nothing re-queued) tests only that nothing
// is heard twice, and the test kills again, up to three rounds.
TEST(NavaAirFaults, NoPacketIsLostOrDuplicatedWhenTheSoundServerRestarts) {
  ASSERT_TRUE(std::getenv("NAVA_AIR_CONTROL")) << "run by test/nava_air.sh, which sets NAVA_AIR_CONTROL";
  constexpr int kRounds = 3;
  int round = 1;
  for (;; ++round) {
    links->Forget();
    const double requeued = std::max(0.0, links->Number("robot_0", "packets re-queued after device faults"));
    for (int k = 1; k <= kPackets; ++k) links->Send(Numbered(k, round));
    ASSERT_TRUE(WaitFor([&] { return links->Numbers("robot_1", round).size() >= 4; }, 20.0)) << links->Describe("robot_1");
    const int rises = links->rises("robot_1");
    ASSERT_TRUE(WaitFor([&] { return links->rises("robot_1") > rises; }, 5.0)) << "the next packet did not start";
    ros::WallDuration(0.15).sleep();
    ASSERT_TRUE(Air("kill")) << "could not kill the sound server";
    const ros::WallTime killed = ros::WallTime::now();
    const bool errors = WaitFor([&] {
      for (const std::string& link : kLinks) {
        if (!links->ErrorSeen(link)) return false;
      }
      return true;
    }, kServerDownSeconds - 0.1);
    WaitFor([] { return false; }, kServerDownSeconds - (ros::WallTime::now() - killed).toSec());
    const std::map<std::string, double> reopens_before = Reopens();
    ASSERT_TRUE(Air("start")) << "could not start the sound server again";
    const ros::Time restarted = ros::Time::now();
    EXPECT_TRUE(errors) << "not every link's diagnostics said ERROR while the server was down";
    ASSERT_TRUE(WaitFor([&] {
      for (const std::string& link : kLinks) {
        if (links->Number(link, "device reopens") <= reopens_before.at(link)) return false;
      }
      return true;
    }, 15.0)) << "not every link reopened";

    const bool all = WaitFor([&] {
      for (const std::string& listener : kListeners) {
        if (static_cast<int>(links->Numbers(listener, round).size()) < kPackets) return false;
      }
      return true;
    }, 60.0);
    // Time for a packet sent twice to arrive twice, and for the diagnostics (once a second).
    WaitFor([] { return false; }, 3.0);
    for (const std::string& listener : kListeners) {
      for (const auto& [k, times] : links->Numbers(listener, round)) {
        EXPECT_EQ(times, 1) << listener << " heard packet " << k << " of round " << round << " that often:" << links->Describe(listener);
      }
    }
    EXPECT_EQ(links->Numbers("robot_0", round).size(), 0u) << "robot_0 heard its own packets";
    const double cut = links->Number("robot_0", "packets re-queued after device faults") - requeued;
    if (cut >= 1.0) {
      // A packet every listener heard garbled after the cut one came through was lost to the
      // air, which is best effort, not to the fault handling: one a round is let pass, said.
      // The shared sound server garbles one now and then within seconds of its clients'
      // reconnecting (seen 2.3 and 4.1 s after the reopen, the 7th and 10th packets; the
      // links' playback reported no underrun, so the gap is the server's own).
      std::set<int> garbled;
      for (int k = 1; k <= kPackets; ++k) {
        bool everywhere = true;
        for (const std::string& listener : kListeners) everywhere = everywhere && links->GarbledLater(listener, k, round, restarted);
        if (everywhere) garbled.insert(k);
      }
      EXPECT_TRUE(all || garbled.size() == 1) << "not every packet was heard";
      EXPECT_LE(garbled.size(), 1u) << "the air garbled more than one packet after the reopen";
      for (const int k : garbled) std::fprintf(stderr, "nava_air_faults_rostest: packet %d garbled in the air after the reopen\n", k);
      for (const std::string& listener : kListeners) {
        const std::map<int, int> numbers = links->Numbers(listener, round);
        for (int k = 1; k <= kPackets; ++k) {
          if (garbled.size() == 1 && garbled.count(k)) continue;
          EXPECT_EQ(numbers.count(k), 1u) << listener << " never heard packet " << k << links->Describe(listener);
        }
      }
      break;
    }
    std::fprintf(stderr, "nava_air_faults_rostest: round %d's kill missed robot_0's packet (nothing re-queued; %s)\n", round,
                 all ? "every packet heard" : "a packet played whole was lost with the listeners' unread capture");
    ASSERT_LT(round, kRounds) << "in " << kRounds << " rounds the kill never fell inside one of robot_0's packets";
  }

  // Every link counted one failure and one reopen a round (diagnostics come once a second), and
  // robot_0 put back the packet the failure cut (and any still in its buffer).
  EXPECT_TRUE(WaitFor([&] {
    for (const std::string& link : kLinks) {
      if (links->Number(link, "device reopens") < round) return false;
    }
    return true;
  }, 5.0));
  for (const std::string& link : kLinks) {
    EXPECT_EQ(links->Value(link, "device"), "open") << link;
    EXPECT_EQ(links->Number(link, "device faults"), round) << link;
    EXPECT_EQ(links->Number(link, "device reopens"), round) << link;
    EXPECT_TRUE(links->LoggedError("/" + link + "/nava_modem", "failed")) << link << " logged no error line";
  }
  EXPECT_GE(links->Number("robot_0", "packets re-queued after device faults"), 1.0);
  EXPECT_EQ(links->Number("robot_1", "packets re-queued after device faults"), 0.0);
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "nava_air_faults_rostest");
  multirobot_audio::Links links;
  multirobot_audio::links = &links;
  return RUN_ALL_TESTS();
}
