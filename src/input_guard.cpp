#include "input_guard.h"

#include <algorithm>
#include <cstdio>

namespace multirobot_audio {
namespace {

// roscpp's counters are read this often (wall s): a connection that closes keeps the counts of
// the last read.
constexpr double kSamplePeriod = 0.2;
// Wall s between two log lines about one input.
constexpr double kWarnPeriod = 5.0;

unsigned long Ul(std::uint64_t n) { return static_cast<unsigned long>(n); }

// "accepted A, rejected R, dropped D, received N", and ", queued Q" for an input's total.
std::string Figures(std::uint64_t accepted, std::uint64_t rejected, std::uint64_t dropped, std::uint64_t received,
                    const std::uint64_t* queued) {
  char text[160];
  std::snprintf(text, sizeof text, "accepted %lu, rejected %lu, dropped %lu, received %lu", Ul(accepted), Ul(rejected),
                Ul(dropped), Ul(received));
  return queued ? std::string(text) + ", queued " + std::to_string(*queued) : std::string(text);
}

}  // namespace

InputGuard::InputGuard() : node_(ros::this_node::getName()) {
  own_updater_ = std::make_unique<diagnostic_updater::Updater>();
  own_updater_->setHardwareID("none");
  own_updater_->add("inputs", this, &InputGuard::Diagnose);
  ros::NodeHandle nh;
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) {
    own_updater_->force_update();
  });
  Start();
}

InputGuard::InputGuard(diagnostic_updater::Updater& updater) : node_(ros::this_node::getName()) {
  updater.add("inputs", this, &InputGuard::Diagnose);
  Start();
}

void InputGuard::Start() {
  ros::NodeHandle nh;
  sample_timer_ = nh.createWallTimer(ros::WallDuration(kSamplePeriod), [this](const ros::WallTimerEvent&) {
    std::lock_guard<std::mutex> lock(mutex_);
    SampleStats();
    const ros::WallTime now = ros::WallTime::now();
    for (Input& input : inputs_) {
      const Row sum = Sum(Rows(input));
      const std::uint64_t queue_drops = sum.dropped;
      if (queue_drops == input.reported_drops || (now - input.last_warning).toSec() < kWarnPeriod) continue;
      ROS_WARN("%s: %s: %lu messages dropped so far (queue full: more came than the node could take)", node_.c_str(),
               input.topic.c_str(), Ul(queue_drops));
      input.reported_drops = queue_drops;
      input.last_warning = now;
    }
  });
}

bool InputGuard::UsesStats() const {
  return std::any_of(inputs_.begin(), inputs_.end(), [](const Input& i) { return !i.numbered; });
}

void InputGuard::SampleStats() {
  // Only inputs without a header take their drops from roscpp (an XML-RPC call to the node).
  if (UsesStats()) stats_.Sample();
}

std::size_t InputGuard::AddInput(const std::string& topic, bool numbered, bool watched) {
  std::lock_guard<std::mutex> lock(mutex_);
  inputs_.push_back(Input{});
  inputs_.back().topic = topic;
  inputs_.back().numbered = numbered;
  inputs_.back().watched = watched;
  return inputs_.size() - 1;
}

void InputGuard::Watch(const std::string& topic) { AddInput(topic, false, true); }

InputGuard::FromPublisher& InputGuard::Publisher(Input& input, const std::string& name) {
  const auto it = input.publishers.find(name);
  if (it != input.publishers.end()) return it->second;
  // Bounded like roscpp's counts (a flood of short-lived nodes must not grow the node).
  if (input.publishers.size() >= SubscriptionStats::kMaxPublishers) {
    return input.publishers[SubscriptionStats::kOtherPublishers];
  }
  return input.publishers[name];
}

std::string InputGuard::Arrive(std::size_t index, const std::string& publisher,
                               const boost::shared_ptr<ros::M_string>& connection, const std_msgs::Header& header,
                               bool check_stamp) {
  std::lock_guard<std::mutex> lock(mutex_);
  FromPublisher& from = Publisher(inputs_[index], publisher);
  // A new connection (the publisher restarted, or reconnected) starts its own numbering and order.
  const boost::shared_ptr<ros::M_string> last = from.connection.lock();
  if (!last || last != connection) {
    from.connection = connection;
    from.has_seq = from.has_stamp = false;
  }
  // Unsigned arithmetic, so that seq may wrap at 2^32. A seq that goes back (no roscpp or rospy
  // publisher's) only starts the count afresh.
  const std::uint32_t gap = header.seq - from.last_seq - 1;
  if (from.has_seq && gap < (1u << 31)) from.dropped += gap;
  from.last_seq = header.seq;
  from.has_seq = true;
  if (!check_stamp) return "";
  const ros::Time& stamp = header.stamp;
  if (!from.has_stamp) {
    from.last_stamp = stamp;
    from.has_stamp = true;
    return "";
  }
  if (stamp < from.last_stamp) {
    char text[128];
    std::snprintf(text, sizeof text, "header.stamp %.3f s is older than %.3f s, the last one accepted", stamp.toSec(),
                  from.last_stamp.toSec());
    return text;
  }
  from.last_stamp = stamp;
  return "";
}

void InputGuard::CountLocked(Input& input, const std::string& publisher, const Verdict& verdict) {
  FromPublisher& from = Publisher(input, publisher);
  if (verdict.kind == Verdict::Kind::kAccepted) {
    ++from.accepted;
    return;
  }
  std::uint64_t& n = verdict.kind == Verdict::Kind::kRejected ? from.rejected : from.dropped;
  ++n;
  input.last_problem = publisher + ": " + verdict.reason;
  const ros::WallTime now = ros::WallTime::now();
  if ((now - input.last_warning).toSec() < kWarnPeriod) return;
  input.last_warning = now;
  ROS_WARN("%s: %s from %s: %s: %s (%lu so far from it)", node_.c_str(), input.topic.c_str(), publisher.c_str(),
           verdict.kind == Verdict::Kind::kRejected ? "rejected" : "dropped", verdict.reason.c_str(), Ul(n));
}

std::map<std::string, InputGuard::Row> InputGuard::Rows(const Input& input) const {
  std::map<std::string, Row> rows;
  if (!input.numbered) {
    for (const auto& [name, counts] : stats_.ByPublisher(input.topic)) {
      rows[name].received = counts.received;
      rows[name].dropped = counts.dropped;
    }
  }
  for (const auto& [name, from] : input.publishers) {
    Row& row = rows[name];
    row.accepted = from.accepted;
    row.rejected = from.rejected;
    row.dropped += from.dropped;
    // Numbered: what the publisher sent over its connections, as far as the last seq seen.
    if (input.numbered) row.received = row.accepted + row.rejected + row.dropped;
  }
  if (input.watched) {
    // What roscpp handed on to the library counts as accepted.
    for (auto& [name, row] : rows) row.accepted = row.received > row.dropped ? row.received - row.dropped : 0;
  }
  return rows;
}

InputGuard::Row InputGuard::Sum(const std::map<std::string, Row>& rows) {
  Row sum;
  for (const auto& [name, row] : rows) {
    sum.received += row.received;
    sum.accepted += row.accepted;
    sum.rejected += row.rejected;
    sum.dropped += row.dropped;
  }
  // Received by roscpp and not yet dropped, rejected or handed on: waiting in the queue (or, in
  // lockstep, for its step). Always 0 for a numbered input, whose queued messages are not
  // counted before they come out.
  const std::uint64_t settled = sum.accepted + sum.rejected + sum.dropped;
  sum.queued = sum.received > settled ? sum.received - settled : 0;
  return sum;
}

void InputGuard::Diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  SampleStats();
  Row all;
  for (const Input& input : inputs_) {
    const std::map<std::string, Row> rows = Rows(input);
    const Row sum = Sum(rows);
    status.add(input.topic, Figures(sum.accepted, sum.rejected, sum.dropped, sum.received, &sum.queued));
    for (const auto& [name, row] : rows) {
      status.add(input.topic + " from " + name, Figures(row.accepted, row.rejected, row.dropped, row.received, nullptr));
    }
    if (!input.last_problem.empty()) status.add(input.topic + " last refused", input.last_problem);
    if (!input.numbered && stats_.Unreported(input.topic) > 0) {
      status.add(input.topic + " drops", "a lower bound: roscpp did not report " +
                                             std::to_string(stats_.Unreported(input.topic)) + " of its connections");
    }
    all.rejected += sum.rejected;
    all.dropped += sum.dropped;
  }
  if (UsesStats()) {  // roscpp's counts (received, queue drops) are as of then
    const ros::WallTime sampled = stats_.last_sample();
    status.add("roscpp counts read (wall s ago)",
               sampled.isZero() ? std::string("never") : std::to_string((ros::WallTime::now() - sampled).toSec()));
  }
  if (all.rejected > 0 || all.dropped > 0) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "%lu messages rejected, %lu dropped", Ul(all.rejected),
                    Ul(all.dropped));
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "every message accepted");
  }
}

std::string InputGuard::Summary() {
  std::lock_guard<std::mutex> lock(mutex_);
  SampleStats();
  Row all;
  std::string details;
  for (const Input& input : inputs_) {
    const Row sum = Sum(Rows(input));
    all.accepted += sum.accepted;
    all.rejected += sum.rejected;
    all.dropped += sum.dropped;
    if (sum.rejected == 0 && sum.dropped == 0) continue;
    char text[256];
    std::snprintf(text, sizeof text, "%s%s %lu rejected, %lu dropped", details.empty() ? "" : "; ",
                  input.topic.c_str(), Ul(sum.rejected), Ul(sum.dropped));
    details += text;
  }
  char text[160];
  std::snprintf(text, sizeof text, "inputs accepted %lu, rejected %lu, dropped %lu", Ul(all.accepted),
                Ul(all.rejected), Ul(all.dropped));
  return details.empty() ? std::string(text) : std::string(text) + " (" + details + ")";
}

}  // namespace multirobot_audio
