// A broken peer against every simulated node (test/hostile_input.test): garbage on each input,
// then a flood at 10 kHz for 10 s on each; every node must stay up, account for every message
// on /diagnostics, and work on once the garbage stops.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <geometry_msgs/Twist.h>
#include <gtest/gtest.h>
#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/ChargingState.h>
#include <multirobot_audio/FiducialArray.h>
#include <multirobot_audio/Job.h>
#include <multirobot_audio/LockState.h>
#include <multirobot_audio/RobotCommands.h>
#include <multirobot_audio/RobotScans.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/LaserScan.h>

#include "conversions.h"
#include "hostile_peer.h"
#include "wait_for.h"

namespace multirobot_audio {
namespace {

using testing::DiagnosticsWatch;
using testing::Feed;
using testing::TypedFeed;
using testing::WaitFor;

const float kNan = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();
// Payload of the peer's own packets: not a lock message, not an announcement.
const std::vector<std::uint8_t> kJunk = {0xEE, 0xEE, 0xEE, 0xEE};

// What each controller published, and whether every number in it was finite.
struct Outputs {
  std::map<std::string, int> count;
  std::map<std::string, int> non_finite;
  std::map<std::string, grid::Pose2D> pose;
  void Command(const std::string& robot, const geometry_msgs::Twist& t) {
    ++count[robot];
    if (!std::isfinite(t.linear.x) || !std::isfinite(t.angular.z)) ++non_finite[robot];
  }
  void Truth(const std::string& robot, const nav_msgs::Odometry& o) {
    pose[robot] = FromPose(o.pose.pose);
    if (!grid::IsFinite(pose[robot])) ++non_finite[robot + " ground truth"];
  }
};

class HostileInputTest : public ::testing::Test {
 protected:
  HostileInputTest() : watch_(nh_) {
    for (const std::string robot : {"robot_0", "robot_1", "robot_2", "robot_3"}) {
      const std::string ns = "/" + robot;
      subs_.push_back(nh_.subscribe<geometry_msgs::Twist>(
          ns + "/cmd_vel", 100,
          boost::function<void(const ros::MessageEvent<geometry_msgs::Twist const>&)>(
              [this, robot](const ros::MessageEvent<geometry_msgs::Twist const>& e) {
                // The peer's own commands to robot_3 come back here too; only the controllers'.
                if (e.getPublisherName() != ros::this_node::getName()) out_.Command(robot, *e.getConstMessage());
              })));
      subs_.push_back(nh_.subscribe<nav_msgs::Odometry>(
          ns + "/ground_truth", 10, [this, robot](const nav_msgs::Odometry::ConstPtr& m) { out_.Truth(robot, *m); }));
    }
    subs_.push_back(nh_.subscribe<LockState>("/robot_3/local_mutex/state", 100,
                                             [this](const LockState::ConstPtr& m) { grants_ = m->grants; }));
    subs_.push_back(nh_.subscribe<ChargingState>("/robot_2/charging_demo/state", 100,
                                                 [this](const ChargingState::ConstPtr& m) {
                                                   ++charging_states_;
                                                   if (!std::isfinite(m->battery)) ++out_.non_finite["robot_2 state"];
                                                 }));
    subs_.push_back(nh_.subscribe<AudioReception>(
        "/robot_2/audio/rx", 100, [this](const AudioReception::ConstPtr& m) {
          if (m->kind == AudioReception::PACKET && m->data == probe_) ++probes_heard_;
        }));
    probe_pub_ = nh_.advertise<AudioPacket>("/robot_0/audio/tx", 10);
    MakeFeeds();
  }

  void MakeFeeds() {
    const world_sim::RobotModel model;
    // world_sim: a robot no controller drives.
    auto& cmd = Add<geometry_msgs::Twist>("world_sim", "/robot_3/cmd_vel", geometry_msgs::Twist());
    cmd.Good()
        .Good([](auto& t) { t.linear.x = 0.2; t.angular.z = 1.0; })  // a small circle
        .Bad([](auto& t) { t.linear.x = kNan; })
        .Bad([](auto& t) { t.angular.z = kInf; })
        .Bad([](auto& t) { t.linear.y = -kInf; });
    drive_ = &cmd;
    // world_sim's team commands (several robots in one message), for the same robot.
    RobotCommands team;
    team.names = {"robot_3"};
    team.commands.resize(1);
    Add<RobotCommands>("world_sim", "/world_sim/robot_commands", team)
        .Good()
        .Good([](auto& c) { c.commands[0].linear.x = 0.2; c.commands[0].angular.z = 1.0; })
        .Bad([](auto& c) { c.commands[0].linear.x = kNan; })
        .Bad([](auto& c) { c.names[0] = "ghost"; })
        .Bad([](auto& c) { c.names.push_back("robot_3"); c.commands.push_back(c.commands[0]); })
        .Bad([](auto& c) { c.commands.clear(); });
    // audio_propagation: robot_2's link (its local_mutex sends there too).
    AudioPacket packet;
    packet.data = kJunk;
    Add<AudioPacket>("audio_propagation", "/robot_2/audio/tx", packet)
        .Good()
        .Bad([](auto& p) { p.data.clear(); })
        .Bad([](auto& p) { p.data.resize(3); })
        .Bad([](auto& p) { p.data.resize(5); })
        .Bad([](auto& p) { p.data.assign(1000, 0x55); })
        .Backwards();
    // Ranges, odometry, markers: as world_sim would send them, then spoilt.
    const std::vector<std::pair<std::string, std::string>> scans = {
        {"robot_0/wanderer", "robot_0"}, {"robot_1/sounds_good_explorer", "robot_1"}, {"robot_2/charging_demo", "robot_2"}};
    for (const auto& [node, robot] : scans) {
      Add<sensor_msgs::LaserScan>(node, "/" + robot + "/scan",
                                  ToLaserScan(std::vector<float>(16, 1.5f), model, robot + "/base_link", ros::Time()))
          .Good()
          .Bad([](auto& s) { s.angle_increment = kNan; })
          .Bad([](auto& s) { s.ranges[2] = -1.0f; })
          .Bad([](auto& s) { s.ranges.resize(40, 1.0f); })
          .Bad([](auto& s) { s.range_max = 0.0f; })
          .Bad([](auto& s) { s.range_max = kInf; })
          .Backwards();
    }
    // A team of wanderers in one process, on scans of its own (its commands go nowhere).
    RobotScans team_scans;
    team_scans.names = {"robot_0", "robot_1"};
    team_scans.scans.assign(2, ToLaserScan(std::vector<float>(16, 1.5f), model, "robot_0/base_link", ros::Time()));
    Add<RobotScans>("wanderers", "/hostile/robot_scans", team_scans)
        .Good()
        .Good([](auto& t) { t.names = {"robot_7"}; t.scans.resize(1); })  // a robot the team does not drive
        .Bad([](auto& t) { t.scans[1].ranges[2] = -1.0f; })
        .Bad([](auto& t) { t.scans[0].angle_increment = kNan; })
        .Bad([](auto& t) { t.scans.pop_back(); })
        .Bad([](auto& t) { t.names[1] = "robot_0"; })
        .Backwards();
    for (const auto& [node, robot] : {std::pair<std::string, std::string>{"robot_1/sounds_good_explorer", "robot_1"},
                                      {"robot_2/charging_demo", "robot_2"}}) {
      Add<nav_msgs::Odometry>(node, "/" + robot + "/odom",
                              ToOdometry({0.1, 0.0, 0.0}, 0.0, 0.0, robot + "/odom", robot + "/base_link", ros::Time()))
          .Good()
          .Bad([](auto& o) { o.pose.pose.position.x = kNan; })
          .Bad([](auto& o) { o.pose.pose.position.y = -kInf; })
          .Bad([](auto& o) { o.pose.pose.orientation = geometry_msgs::Quaternion(); o.pose.pose.orientation.w = 0.0; })
          .Bad([](auto& o) { o.twist.twist.angular.z = kInf; })
          .Backwards();
      FiducialArray none;
      none.header.frame_id = robot + "/base_link";
      Add<FiducialArray>(node, "/" + robot + "/fiducials", none)
          .Good()
          .Bad([](auto& f) { f.fiducials.push_back(Sighting(kNan, 0.0f)); })
          .Bad([](auto& f) { f.fiducials.push_back(Sighting(1.0f, kInf)); })
          .Bad([](auto& f) { f.fiducials.push_back(Sighting(-1.0f, 0.0f)); })
          .Backwards();
    }
    // The charging robot's battery and its view of the lock.
    Add<sensor_msgs::BatteryState>("robot_2/charging_demo", "/robot_2/battery",
                                   ToBatteryState(0.9, false, model.battery, "robot_2/base_link", ros::Time()))
        .Good()
        .Bad([](auto& b) { b.percentage = kNan; b.charge = kNan; })
        .Bad([](auto& b) { b.percentage = -0.5f; })
        .Backwards();
    LockState released;
    released.robot_id = 2;
    Add<LockState>("robot_2/charging_demo", "/robot_2/local_mutex/state", released)
        .Good()
        .Bad([](auto& s) { s.state = 7; })
        .Bad([](auto& s) { s.time_in_state = kNan; })
        .Backwards();
    // Receptions: noise, and a packet of no known kind with no direction (both legitimate).
    AudioReception noise;
    noise.kind = AudioReception::NOISE;
    noise.noise = AudioReception::ZERO_BYTE;
    noise.level_db = 50.0f;
    noise.direction = kNan;
    noise.quality = 1.0f;
    noise.path_length = kNan;
    for (const auto& [node, robot] : {std::pair<std::string, std::string>{"robot_3/local_mutex", "robot_3"},
                                      {"robot_1/sounds_good_explorer", "robot_1"}}) {
      Add<AudioReception>(node, "/" + robot + "/audio/rx", noise)
          .Good()
          .Good([](auto& r) { r.kind = AudioReception::PACKET; r.noise = AudioReception::NONE; r.data = kJunk; })
          .Bad([](auto& r) { r.level_db = kNan; })
          .Bad([](auto& r) { r.direction = kInf; })
          .Bad([](auto& r) { r.direction_confidence = kNan; })
          .Bad([](auto& r) { r.kind = 9; })
          .Bad([](auto& r) { r.path_length = -1.0f; })
          .Backwards();
    }
    // task_monitor: jobs from a robot that has no explorer, and a count of 0 for one that has.
    auto next = std::make_shared<std::uint32_t>(0);
    Job job;
    job.count = 1;
    jobs_ = &Add<Job>("task_monitor", "/robot_0/jobs", job)
                 .Good([next](auto& j) { j.count = ++*next; })
                 .Bad([](auto& j) { j.count = 0; })
                 .Bad([next](auto& j) { j.count = *next; })  // the same count again
                 .Backwards();
    Add<Job>("task_monitor", "/robot_1/jobs", job).Bad([](auto& j) { j.count = 0; });
  }

  static Fiducial Sighting(float range, float bearing) {
    Fiducial f;
    f.id = 100;
    f.range = range;
    f.bearing = bearing;
    return f;
  }

  template <class M>
  TypedFeed<M>& Add(const std::string& node, const std::string& topic, M valid) {
    auto feed = std::make_unique<TypedFeed<M>>(nh_, node, topic, std::move(valid));
    TypedFeed<M>& ref = *feed;
    feeds_.push_back(std::move(feed));
    return ref;
  }

  std::vector<Feed*> Feeds(const std::vector<std::string>& nodes) const {
    std::vector<Feed*> out;
    for (const auto& f : feeds_) {
      if (nodes.empty() || std::find(nodes.begin(), nodes.end(), f->node()) != nodes.end()) out.push_back(f.get());
    }
    return out;
  }

  ros::NodeHandle nh_;
  DiagnosticsWatch watch_;
  std::vector<std::unique_ptr<Feed>> feeds_;
  Feed* drive_ = nullptr;
  Feed* jobs_ = nullptr;
  std::vector<ros::Subscriber> subs_;
  ros::Publisher probe_pub_;
  Outputs out_;
  std::uint64_t grants_ = 0;
  int charging_states_ = 0;
  std::vector<std::uint8_t> probe_ = {0x5A, 0xA5, 0x5A, 0xA5};
  int probes_heard_ = 0;
};

const std::vector<std::string> kNodes = {"world_sim",           "audio_propagation",
                                         "robot_0/wanderer",    "wanderers",
                                         "robot_1/sounds_good_explorer",
                                         "robot_2/charging_demo", "robot_2/local_mutex",
                                         "robot_3/local_mutex", "robot_3/mutex_client",
                                         "task_monitor"};

TEST_F(HostileInputTest, EveryNodeCountsEveryMessageAndWorksOn) {
  const ros::WallTime start = ros::WallTime::now();
  // Everyone up: every node reports its inputs, every feed reaches its node, the clock runs.
  // Under a loaded CI machine (a compiler beside the test) ten nodes can take long to come up,
  // so the wait is generous, and a failure names what was missing.
  const auto missing = [&] {
    std::string what;
    for (const std::string& node : kNodes) {
      const double age = watch_.Age(node + ": inputs");
      if (age > 2.0) what += " " + node + " (diagnostics " + std::to_string(age) + " s old)";
    }
    for (const auto& f : feeds_) {
      if (!f->Connected()) what += " feed " + f->topic() + " (unconnected)";
    }
    if (ros::Time::now().toSec() <= 2.0) what += " sim clock at " + std::to_string(ros::Time::now().toSec()) + " s";
    if (grants_ == 0) what += " robot_3's mutex has granted nothing";
    return what;
  };
  ASSERT_TRUE(WaitFor([&] { return missing().empty(); }, 120.0))
      << "not everything came up within 120 s:" << missing();
  std::printf("hostile_input: everything up after %.0f s (wall)\n", (ros::WallTime::now() - start).toSec());

  // 1. Each kind of garbage once: each must be rejected, each good message accepted.
  testing::SendEachOnce(Feeds({}));
  testing::ExpectAccounted(watch_, Feeds({}), true, 15.0);

  // 2. Floods, 10 kHz for 10 s on each input, in two waves (the machine has two cores).
  const std::vector<std::vector<std::string>> waves = {
      {"world_sim", "audio_propagation", "robot_0/wanderer", "wanderers", "robot_3/local_mutex", "task_monitor"},
      {"robot_1/sounds_good_explorer", "robot_2/charging_demo"}};
  for (const auto& wave : waves) {
    const std::vector<Feed*> feeds = Feeds(wave);
    const std::vector<double> rates = testing::Flood(feeds, 10000.0, 10.0);
    for (std::size_t i = 0; i < feeds.size(); ++i) {
      std::printf("hostile_input: flood of %s (%s): %.0f messages/s\n", feeds[i]->topic().c_str(),
                  feeds[i]->node().c_str(), rates[i]);
    }
  }
  std::fflush(stdout);
  testing::SendClosing(Feeds({}));
  // The wait ends once every count has settled, 5 to 15 s on a quiet machine; beside a build
  // on both cores, the flooded nodes once needed more than 30 s to work through some 80,000
  // messages each.
  testing::ExpectAccounted(watch_, Feeds({}), false, 90.0);

  // 3. Afterwards: every node still up and working.
  const std::uint64_t grants = grants_;
  const int states = charging_states_;
  std::map<std::string, int> commands = out_.count;
  const std::map<std::string, grid::Pose2D> before = out_.pose;
  // robot_3 driven by the peer, now sanely; robot_0 by its wanderer.
  const ros::WallTime drive_until = ros::WallTime::now() + ros::WallDuration(3.0);
  WaitFor([&] {
    drive_->Send(1);
    return ros::WallTime::now() > drive_until;
  }, 5.0);
  for (const std::string robot : {"robot_0", "robot_3"}) {
    const grid::Pose2D& a = before.at(robot);
    const grid::Pose2D& b = out_.pose[robot];
    EXPECT_TRUE(std::hypot(b.x - a.x, b.y - a.y) > 0.05 || std::abs(grid::NormalizeAngle(b.yaw - a.yaw)) > 0.3)
        << robot << " did not move after the flood";
  }
  // The audio link still delivers (robot_2's link first sends what the flood queued).
  ros::WallTime next;
  EXPECT_TRUE(WaitFor([&] {
    if (ros::WallTime::now() > next) {
      AudioPacket p;
      p.header.stamp = ros::Time::now();
      p.data = probe_;
      probe_pub_.publish(p);
      next = ros::WallTime::now() + ros::WallDuration(2.0);
    }
    return probes_heard_ > 0;
  }, 40.0)) << "robot_2 never heard robot_0's packet after the flood";
  // The mutex still grants, the explorer and the charging robot still steer and report.
  EXPECT_TRUE(WaitFor([&] { return grants_ > grants; }, 40.0)) << "robot_3's mutex granted nothing after the flood";
  EXPECT_TRUE(WaitFor([&] { return charging_states_ > states + 2; }, 20.0)) << "charging_demo stopped reporting";
  for (const std::string robot : {"robot_0", "robot_1", "robot_2"}) {
    EXPECT_GT(out_.count[robot], commands[robot] + 5) << robot << "'s controller stopped steering";
  }
  // task_monitor still counts a good job.
  jobs_->Send(0);
  testing::ExpectAccounted(watch_, {jobs_}, false, 10.0);
  EXPECT_EQ(out_.non_finite.size(), 0u) << "a controller or the world published a non-finite number";
  for (const auto& [what, n] : out_.non_finite) ADD_FAILURE() << what << ": " << n << " non-finite messages";

  // The robot missing from TF: audio_propagation says so, and serves the others.
  EXPECT_EQ(watch_.Value("audio_propagation: poses", "ghost").rfind("no pose yet", 0), 0u)
      << watch_.Value("audio_propagation: poses", "ghost");
  EXPECT_EQ(watch_.Value("audio_propagation: poses", "robot_0").rfind("pose ", 0), 0u);
  EXPECT_EQ(watch_.Level("audio_propagation: poses"), diagnostic_msgs::DiagnosticStatus::WARN);

  for (const std::string& node : kNodes) {
    EXPECT_LT(watch_.Age(node + ": inputs"), 3.0) << node << " stopped reporting (died?)";
    std::printf("hostile_input: %s: %s\n", node.c_str(), watch_.Message(node + ": inputs").c_str());
  }
  std::printf("hostile_input: test took %.0f s (wall)\n", (ros::WallTime::now() - start).toSec());
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "hostile_input");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
