// launch/team_robots.launch brought up on this machine alone (every host localhost), each robot's
// nava_modem on one PulseAudio "air" (test/team_robots.test, run by test/nava_air.sh): every
// robot's link and controller run in its own namespace with its robot_id as seed, no topic
// carries messages from one robot's nodes to another's, and with ~announcements the wanderers'
// announcements cross the air from robot to robot.
//
// Parameters: ~ids (the robots' robot_ids, robot_k's first), ~controller (the task's node),
// ~announcements (wait for the wanderers' packets).
#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <multirobot_audio/AudioReception.h>
#include <ros/master.h>
#include <ros/ros.h>

#include "wait_for.h"

namespace multirobot_audio {
namespace {

using testing::WaitFor;

std::vector<int> ids;
std::string controller;
bool announcements = false;

std::string Robot(std::size_t k) { return "/robot_" + std::to_string(k); }

std::set<std::string> Nodes() {
  std::vector<std::string> nodes;
  ros::master::getNodes(nodes);
  return {nodes.begin(), nodes.end()};
}

std::map<std::string, std::string> TopicTypes() {
  ros::master::V_TopicInfo topics;
  ros::master::getTopics(topics);
  std::map<std::string, std::string> out;
  for (const ros::master::TopicInfo& t : topics) out[t.name] = t.datatype;
  return out;
}

std::string List(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += " " + n;
  return out;
}

TEST(TeamRobots, EachRobotsLinkAndControllerRunInItsNamespace) {
  std::set<std::string> expected;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    expected.insert(Robot(k) + "/nava_modem");
    expected.insert(Robot(k) + "/" + controller);
  }
  const bool up = WaitFor([&] {
    const std::set<std::string> nodes = Nodes();
    return std::includes(nodes.begin(), nodes.end(), expected.begin(), expected.end());
  }, 30.0);
  ASSERT_TRUE(up) << "expected" << List(expected) << "; the master has" << List(Nodes());
  // No robot beyond the hosts given.
  for (const std::string& node : Nodes()) EXPECT_NE(node.rfind(Robot(ids.size()) + "/", 0), 0u) << node;

  // Each link serves its robot's topics, under its robot's namespace.
  EXPECT_TRUE(WaitFor([&] {
    const std::map<std::string, std::string> topics = TopicTypes();
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const auto rx = topics.find(Robot(k) + "/audio/rx");
      if (rx == topics.end() || rx->second != "multirobot_audio/AudioReception") return false;
      if (topics.count(Robot(k) + "/audio/carrier") == 0) return false;
    }
    return true;
  }, 10.0)) << "a robot's audio/rx or audio/carrier is missing";

  for (std::size_t k = 0; k < ids.size(); ++k) {
    for (const std::string& node : {std::string("nava_modem"), controller}) {
      int seed = -1;
      EXPECT_TRUE(ros::param::get(Robot(k) + "/" + node + "/seed", seed)) << Robot(k) << "/" << node;
      EXPECT_EQ(seed, ids[k]) << Robot(k) << "/" << node << " must be seeded with its robot_id";
    }
    int robot_id = -1;
    if (ros::param::get(Robot(k) + "/" + controller + "/robot_id", robot_id)) {
      EXPECT_EQ(robot_id, ids[k]) << Robot(k) << "/" << controller;
    }
  }
}

// One edge of the topic graph: a topic, a node publishing it and a node subscribing to it.
struct Edge {
  std::string topic, publisher, subscriber;
};

// The master's topic graph now, less the log and the team's packet timings for two-way
// ranging (a side channel by design).
std::vector<Edge> TopicEdges() {
  XmlRpc::XmlRpcValue args, result, state;
  args[0] = ros::this_node::getName();
  std::vector<Edge> edges;
  if (!ros::master::execute("getSystemState", args, result, state, true)) return edges;
  // state: [publishers, subscribers, services], each a list of [topic, [node, ...]]
  std::map<std::string, std::set<std::string>> ends[2];  // [publishers, subscribers]: topic -> nodes
  for (int side = 0; side < 2; ++side) {
    for (int t = 0; t < state[side].size(); ++t) {
      for (int n = 0; n < state[side][t][1].size(); ++n) {
        ends[side][static_cast<std::string>(state[side][t][0])].insert(static_cast<std::string>(state[side][t][1][n]));
      }
    }
  }
  for (const auto& [topic, subscribers] : ends[1]) {
    if (topic == "/rosout" || topic == "/audio/timings") continue;
    for (const std::string& sub : subscribers) {
      for (const std::string& pub : ends[0][topic]) edges.push_back({topic, pub, sub});
    }
  }
  return edges;
}

// "/robot_1" for "/robot_1/nava_modem"; a node outside the robots stands for itself.
std::string Owner(const std::string& node) {
  return node.rfind("/robot_", 0) == 0 ? node.substr(0, node.find('/', 1)) : node;
}

// In the topic graph, robot_k's nodes publish to and subscribe from robot_k's nodes only: on
// real robots, where each robot's nodes share its machine, their messages need no network but
// /rosout's (log lines to the master's machine) and what others subscribe to. (/diagnostics has
// every robot's link as publisher and, here, no subscriber.) A node registers its publishers and
// subscribers one by one after it appears, so the graph is read once every controller has
// connected to its own link (CI once read it with one controller still registering).
TEST(TeamRobots, NoMessageGoesFromOneRobotToAnother) {
  std::vector<Edge> edges;
  auto each_controller_linked = [&] {
    edges = TopicEdges();
    std::set<std::string> linked;  // robots whose controller and link share a topic
    for (const Edge& e : edges) {
      if (Owner(e.publisher) == Owner(e.subscriber) && e.publisher != e.subscriber) linked.insert(Owner(e.publisher));
    }
    return linked.size() >= ids.size();
  };
  EXPECT_TRUE(WaitFor(each_controller_linked, 30.0)) << "each robot's controller talks to its link";
  ASSERT_FALSE(edges.empty()) << "the master's system state is empty";
  for (const Edge& e : edges) {
    EXPECT_EQ(Owner(e.publisher), Owner(e.subscriber)) << e.topic << ": " << e.publisher << " publishes to " << e.subscriber;
  }
}

// The wanderers announce 'W' and their seed's low three bytes: robot_k's announcement is
// {'W', 0, 0, ids[k]} for ids below 256.
TEST(TeamRobots, EachRobotHearsAnotherRobotsAnnouncementOverTheAir) {
  if (!announcements) GTEST_SKIP() << "this task makes no announcements";
  ros::NodeHandle nh;
  std::map<std::size_t, std::set<int>> heard;  // robot -> ids it heard announce
  std::vector<ros::Subscriber> subs;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    subs.push_back(nh.subscribe<AudioReception>(Robot(k) + "/audio/rx", 100, [&heard, k](const AudioReception::ConstPtr& r) {
      if (r->kind == AudioReception::PACKET && r->data.size() == 4 && r->data[0] == 'W') heard[k].insert(r->data[3]);
    }));
  }
  auto each_heard_another = [&] {
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const std::set<int>& from = heard[k];
      if (std::none_of(from.begin(), from.end(), [&](int id) { return id != ids[k]; })) return false;
    }
    return true;
  };
  const bool crossed = WaitFor(each_heard_another, 60.0);
  std::string report;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    report += "\n" + Robot(k) + " heard ids:";
    for (int id : heard[k]) report += " " + std::to_string(id);
  }
  EXPECT_TRUE(crossed) << "within 60 s:" << report;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    for (int id : heard[k]) {
      EXPECT_TRUE(std::find(ids.begin(), ids.end(), id) != ids.end()) << Robot(k) << " heard unknown id " << id;
    }
  }
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "team_robots_rostest");
  ros::NodeHandle pnh("~");
  pnh.getParam("ids", multirobot_audio::ids);
  pnh.getParam("controller", multirobot_audio::controller);
  pnh.getParam("announcements", multirobot_audio::announcements);
  if (multirobot_audio::ids.empty() || multirobot_audio::controller.empty()) {
    std::fprintf(stderr, "team_robots_rostest: ~ids and ~controller must be set\n");
    return 1;
  }
  return RUN_ALL_TESTS();
}
