#include "hostile_peer.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <limits>
#include <regex>

#include <gtest/gtest.h>

#include "wait_for.h"

namespace multirobot_audio::testing {
namespace {

std::string StatusName(const std::string& node) { return node + ": inputs"; }

InputFigures Parse(const std::string& value) {
  static const std::regex figures(
      R"(accepted (\d+), rejected (\d+), dropped (\d+), received (\d+)(, queued (\d+))?)");
  std::smatch m;
  InputFigures f;
  if (!std::regex_search(value, m, figures)) return f;
  f.found = true;
  f.accepted = std::stoull(m[1]);
  f.rejected = std::stoull(m[2]);
  f.dropped = std::stoull(m[3]);
  f.received = std::stoull(m[4]);
  f.queued = m[6].matched ? std::stoull(m[6]) : 0;
  return f;
}

}  // namespace

DiagnosticsWatch::DiagnosticsWatch(ros::NodeHandle nh) {
  sub_ = nh.subscribe("/diagnostics", 1000, &DiagnosticsWatch::OnDiagnostics, this);
}

void DiagnosticsWatch::OnDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
  for (const auto& status : msg->status) {
    latest_[status.name] = status;
    seen_[status.name] = ros::WallTime::now();
  }
}

std::string DiagnosticsWatch::Value(const std::string& name, const std::string& key) const {
  const auto it = latest_.find(name);
  if (it == latest_.end()) return "";
  for (const auto& kv : it->second.values) {
    if (kv.key == key) return kv.value;
  }
  return "";
}

std::string DiagnosticsWatch::Message(const std::string& name) const {
  const auto it = latest_.find(name);
  return it == latest_.end() ? "" : it->second.message;
}

int DiagnosticsWatch::Level(const std::string& name) const {
  const auto it = latest_.find(name);
  return it == latest_.end() ? -1 : it->second.level;
}

double DiagnosticsWatch::Age(const std::string& name) const {
  const auto it = seen_.find(name);
  return it == seen_.end() ? std::numeric_limits<double>::infinity() : (ros::WallTime::now() - it->second).toSec();
}

InputFigures DiagnosticsWatch::Figures(const std::string& node, const std::string& topic,
                                       const std::string& publisher) const {
  return Parse(Value(StatusName(node), publisher.empty() ? topic : topic + " from " + publisher));
}

void SendEachOnce(const std::vector<Feed*>& feeds) {
  for (Feed* feed : feeds) {
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t v = 0; v < feed->variants(); ++v) {
        if (feed->good(v) != (pass == 0)) continue;
        feed->Send(v);
        ros::WallDuration(0.003).sleep();
      }
    }
  }
}

std::vector<double> Flood(const std::vector<Feed*>& feeds, double rate, double seconds) {
  std::vector<std::uint64_t> sent(feeds.size(), 0);
  const ros::WallTime start = ros::WallTime::now();
  for (;;) {
    const double elapsed = (ros::WallTime::now() - start).toSec();
    if (elapsed >= seconds) break;
    const auto due = static_cast<std::uint64_t>(elapsed * rate);
    bool behind = false;
    for (std::size_t i = 0; i < feeds.size(); ++i) {
      // At most a millisecond's worth at a time, so that the feeds take turns.
      for (int burst = 0; sent[i] < due && burst < std::max(1, static_cast<int>(rate / 1000.0)); ++burst) {
        feeds[i]->Send(sent[i] % feeds[i]->variants());
        ++sent[i];
      }
      behind = behind || sent[i] < due;
    }
    if (!behind) ros::WallDuration(0.0002).sleep();
  }
  const double wall = (ros::WallTime::now() - start).toSec();
  std::vector<double> rates;
  for (const std::uint64_t n : sent) rates.push_back(static_cast<double>(n) / wall);
  return rates;
}

void SendClosing(const std::vector<Feed*>& feeds) {
  for (Feed* feed : feeds) {
    feed->Send(0);
    ros::WallDuration(0.003).sleep();
  }
}

void ExpectAccounted(const DiagnosticsWatch& watch, const std::vector<Feed*>& feeds, bool exact,
                     double wall_seconds) {
  const std::string me = ros::this_node::getName();
  auto settled = [&](const Feed* f) {
    const InputFigures mine = watch.Figures(f->node(), f->topic(), me);
    const InputFigures all = watch.Figures(f->node(), f->topic());
    return mine.received == f->sent() && mine.settled() == f->sent() && all.found && all.queued == 0;
  };
  WaitFor([&] { return std::all_of(feeds.begin(), feeds.end(), settled); }, wall_seconds);
  for (const Feed* f : feeds) {
    const InputFigures mine = watch.Figures(f->node(), f->topic(), me);
    const InputFigures all = watch.Figures(f->node(), f->topic());
    char line[400];
    std::snprintf(line, sizeof line,
                  "%-28s %-26s sent %6" PRIu64 " (%6" PRIu64 " bad): accepted %6" PRIu64 ", rejected %6" PRIu64
                  ", dropped %6" PRIu64 ", received %6" PRIu64 " (all publishers: %" PRIu64 ", %" PRIu64 ", %" PRIu64
                  ", queued %" PRIu64 ")",
                  f->node().c_str(), f->topic().c_str(), f->sent(), f->bad_sent(), mine.accepted, mine.rejected,
                  mine.dropped, mine.received, all.accepted, all.rejected, all.dropped, all.queued);
    std::printf("hostile_peer: %s\n", line);
    // The figures go into every failure's message too: the log of a failed run under rostest
    // shows the assertions, not this node's output.
    const std::string what = std::string(line) + ": ";
    EXPECT_TRUE(mine.found && all.found) << what << "no figures on /diagnostics for " << me;
    EXPECT_EQ(mine.settled(), f->sent()) << what << "accepted + rejected + dropped must be every message sent";
    EXPECT_EQ(mine.received, f->sent()) << what << "not every message sent was seen to arrive";
    EXPECT_EQ(all.queued, 0u) << what << "messages left in the queue long after the flood";
    if (exact && mine.dropped == 0) {
      EXPECT_EQ(mine.accepted, f->good_sent()) << what << "a good message turned down";
      EXPECT_EQ(mine.rejected, f->bad_sent()) << what << "a bad message let through";
    }
  }
  std::fflush(stdout);
}

}  // namespace multirobot_audio::testing
