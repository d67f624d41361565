#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>

#include <ros/ros.h>

namespace multirobot_audio {

// What roscpp itself counts on each connection from a publisher to one of this node's
// subscriptions: the messages that arrived, and those it dropped because the subscription's
// queue was full (roscpp then discards the oldest queued message and says so nowhere else).
// These are the figures of the node's bus statistics, which roscpp gives only through its slave
// XML-RPC API (getBusStats, getBusInfo): asked here of the node's own server, put down to
// publisher nodes, and kept when a connection closes. roscpp 1.15's getBusStats reports one
// connection per topic (the last; its Subscription::getStats never moves to the next row), so
// a topic with several publishers is counted short: Unreported() says by how many connections.
// And when a full queue drops its oldest message, roscpp counts the drop against the connection
// whose message arrived, which need not be the one whose message went.
//
// Sample() reads them; a connection that closes keeps the counts of its last sample, so call it
// often (the drops of a connection's last moments before it closes may be missed).
class SubscriptionStats {
 public:
  struct Counts {
    std::uint64_t received = 0;
    std::uint64_t dropped = 0;
  };
  // Publishers of one topic beyond this many are counted together as kOtherPublishers.
  static constexpr std::size_t kMaxPublishers = 32;
  static constexpr const char* kOtherPublishers = "(other publishers)";

  // Reads roscpp's counters now; false when the node's server did not answer (the counts stay as
  // last read). A connection from a publisher not yet known by name is put down to its node
  // through the master (at most once a second while any stays unknown).
  bool Sample();
  // Connections to `topic` that roscpp had but did not report at the last Sample().
  std::size_t Unreported(const std::string& topic) const;
  // Wall time of the last successful Sample() (zero before the first).
  ros::WallTime last_sample() const { return last_sample_; }

  // Totals per publisher node for `topic` (a resolved name), over every connection so far. A
  // publisher the master has not named yet is shown under its XML-RPC address.
  std::map<std::string, Counts> ByPublisher(const std::string& topic) const;

 private:
  struct Link {
    std::string topic, uri;
    std::string name;  // the publisher node (its address until the master has said)
    Counts counts;
  };
  using Key = std::pair<std::string, std::string>;  // (topic, publisher node)

  std::string PublisherName(const std::string& topic, const std::string& uri);
  void LookUpNames();

  std::map<int, Link> open_;                   // connection id -> link
  std::map<Key, Counts> closed_;               // totals of the connections that are gone
  std::map<std::string, std::string> names_;   // publisher XML-RPC URI -> node name
  std::map<std::string, std::set<std::string>> publishers_;  // topic -> publisher nodes counted apart
  std::map<std::string, std::size_t> unreported_;              // topic -> connections roscpp left out
  ros::WallTime last_lookup_, last_sample_;
};

}  // namespace multirobot_audio
