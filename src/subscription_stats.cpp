#include "subscription_stats.h"

#include <ros/master.h>
#include <ros/network.h>
#include <ros/xmlrpc_manager.h>
#include <xmlrpcpp/XmlRpcClient.h>

namespace multirobot_audio {
namespace {

bool IsInt(const XmlRpc::XmlRpcValue& v) { return v.getType() == XmlRpc::XmlRpcValue::TypeInt; }
bool IsString(const XmlRpc::XmlRpcValue& v) { return v.getType() == XmlRpc::XmlRpcValue::TypeString; }
bool IsArray(const XmlRpc::XmlRpcValue& v, int size) {
  return v.getType() == XmlRpc::XmlRpcValue::TypeArray && v.size() >= size;
}
// roscpp hands its 64-bit counters over as XML-RPC ints (32 bits, signed).
std::uint64_t Count(XmlRpc::XmlRpcValue& v) {
  return IsInt(v) ? static_cast<std::uint32_t>(static_cast<int>(v)) : 0;
}

// Names kept of publisher addresses no open connection uses any more, at most.
constexpr std::size_t kMaxStaleNames = 256;

// Asks this node's own XML-RPC server (roscpp answers there in a thread of its own) for
// `method`'s payload: the slave API's getBusStats and getBusInfo are how roscpp tells anyone its
// connections' counts. False when it does not answer (the node is shutting down).
bool AskSelf(const char* method, XmlRpc::XmlRpcValue& payload) {
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(ros::XMLRPCManager::instance()->getServerURI(), host, port)) return false;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue args, result;
  args[0] = ros::this_node::getName();
  if (!client.execute(method, args, result) || client.isFault()) return false;
  // [status code, status message, payload], code 1 for success; but roscpp's getBusStats
  // answers with the bare payload ([publications, subscriptions, ...]).
  if (IsArray(result, 3) && IsInt(result[0])) {
    if (static_cast<int>(result[0]) != 1) return false;
    payload = result[2];
    return true;
  }
  if (!IsArray(result, 2)) return false;
  payload = result;
  return true;
}

}  // namespace

bool SubscriptionStats::Sample() {
  XmlRpc::XmlRpcValue stats, info;
  if (!AskSelf("getBusStats", stats) || !AskSelf("getBusInfo", info)) return false;

  // Connection id -> (topic, publisher address), for the subscriptions ("i": inbound).
  std::map<int, std::pair<std::string, std::string>> inbound;
  for (int i = 0; i < info.size(); ++i) {
    XmlRpc::XmlRpcValue& c = info[i];
    if (!IsArray(c, 5) || !IsInt(c[0]) || !IsString(c[1]) || !IsString(c[2]) || !IsString(c[4])) continue;
    if (static_cast<std::string>(c[2]) != "i") continue;
    inbound[static_cast<int>(c[0])] = {static_cast<std::string>(c[4]), static_cast<std::string>(c[1])};
  }

  // stats[1]: per subscription, [topic, [[connection id, bytes, messages, drops, ...], ...]].
  std::set<int> seen;
  unreported_.clear();
  for (const auto& [id, where] : inbound) ++unreported_[where.first];
  if (IsArray(stats, 2) && stats[1].getType() == XmlRpc::XmlRpcValue::TypeArray) {
    XmlRpc::XmlRpcValue& subscriptions = stats[1];
    for (int s = 0; s < subscriptions.size(); ++s) {
      if (!IsArray(subscriptions[s], 2) || !IsArray(subscriptions[s][1], 0)) continue;
      XmlRpc::XmlRpcValue& links = subscriptions[s][1];
      for (int l = 0; l < links.size(); ++l) {
        XmlRpc::XmlRpcValue& link = links[l];
        if (!IsArray(link, 4) || !IsInt(link[0])) continue;
        const int id = static_cast<int>(link[0]);
        const auto where = inbound.find(id);
        if (where == inbound.end()) {
          // Changed between the two reads: keep what the last sample said, or wait for the next.
          if (open_.count(id)) seen.insert(id);
          continue;
        }
        Link& open = open_[id];
        open.topic = where->second.first;
        open.uri = where->second.second;
        open.counts.received = Count(link[2]);
        open.counts.dropped = Count(link[3]);
        seen.insert(id);
        --unreported_[open.topic];
      }
    }
  }

  bool unknown = false;
  for (const auto& [id, link] : open_) unknown = unknown || names_.count(link.uri) == 0;
  if (unknown) LookUpNames();
  for (auto& [id, link] : open_) {
    if (link.name.empty() || link.name == link.uri) link.name = PublisherName(link.topic, link.uri);
  }

  for (auto it = open_.begin(); it != open_.end();) {
    if (seen.count(it->first)) {
      ++it;
      continue;
    }
    const Link& gone = it->second;
    Counts& total = closed_[{gone.topic, gone.name}];
    total.received += gone.counts.received;
    total.dropped += gone.counts.dropped;
    it = open_.erase(it);
  }

  if (names_.size() > kMaxStaleNames) {
    std::set<std::string> in_use;
    for (const auto& [id, link] : open_) in_use.insert(link.uri);
    for (auto it = names_.begin(); it != names_.end();) it = in_use.count(it->first) ? std::next(it) : names_.erase(it);
  }
  last_sample_ = ros::WallTime::now();
  return true;
}

void SubscriptionStats::LookUpNames() {
  const ros::WallTime now = ros::WallTime::now();
  if (!last_lookup_.isZero() && (now - last_lookup_).toSec() < 1.0) return;
  last_lookup_ = now;
  // The master says who publishes each topic, and where each node answers.
  XmlRpc::XmlRpcValue args, result, state;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, state, false) || !IsArray(state, 1)) return;
  std::set<std::string> topics, nodes;
  for (const auto& [id, link] : open_) topics.insert(link.topic);
  XmlRpc::XmlRpcValue& publications = state[0];
  for (int i = 0; i < publications.size(); ++i) {
    if (!IsArray(publications[i], 2) || !IsString(publications[i][0])) continue;
    if (!topics.count(static_cast<std::string>(publications[i][0]))) continue;
    XmlRpc::XmlRpcValue& who = publications[i][1];
    for (int k = 0; k < who.size(); ++k) {
      if (IsString(who[k])) nodes.insert(static_cast<std::string>(who[k]));
    }
  }
  std::set<std::string> known;
  for (const auto& [uri, name] : names_) known.insert(name);
  for (const std::string& node : nodes) {
    if (known.count(node)) continue;
    XmlRpc::XmlRpcValue lookup, answer, uri;
    lookup[0] = ros::this_node::getName();
    lookup[1] = node;
    if (ros::master::execute("lookupNode", lookup, answer, uri, false) && IsString(uri)) {
      names_[static_cast<std::string>(uri)] = node;
    }
  }
}

std::string SubscriptionStats::PublisherName(const std::string& topic, const std::string& uri) {
  const auto it = names_.find(uri);
  const std::string name = it == names_.end() ? uri : it->second;
  std::set<std::string>& counted = publishers_[topic];
  if (counted.count(name)) return name;
  if (counted.size() >= kMaxPublishers) return kOtherPublishers;
  counted.insert(name);
  return name;
}

std::size_t SubscriptionStats::Unreported(const std::string& topic) const {
  const auto it = unreported_.find(topic);
  return it == unreported_.end() ? 0 : it->second;
}

std::map<std::string, SubscriptionStats::Counts> SubscriptionStats::ByPublisher(const std::string& topic) const {
  std::map<std::string, Counts> out;
  for (const auto& [key, counts] : closed_) {
    if (key.first != topic) continue;
    out[key.second].received += counts.received;
    out[key.second].dropped += counts.dropped;
  }
  for (const auto& [id, link] : open_) {
    if (link.topic != topic) continue;
    out[link.name].received += link.counts.received;
    out[link.name].dropped += link.counts.dropped;
  }
  return out;
}

}  // namespace multirobot_audio
