// The message checks every node's InputGuard runs: what world_sim and audio_propagation publish
// passes; each kind of garbage a broken peer sends is named by field and value.
#include "input_checks.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "conversions.h"

namespace multirobot_audio {
namespace {

const float kNan = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

world_sim::RobotModel Model() { return world_sim::RobotModel{}; }

// `msg` with `spoil` done to it.
template <class M, class F>
M Spoilt(M msg, F spoil) {
  spoil(msg);
  return msg;
}

TEST(InputChecksTest, TwistNeedsEveryNumberFinite) {
  geometry_msgs::Twist t;
  t.linear.x = 0.3;
  t.angular.z = -1.0;
  EXPECT_EQ(TwistProblem(t), "");
  t.angular.z = kNan;
  EXPECT_EQ(TwistProblem(t), "angular.z = nan");
  t.angular.z = 0.0;
  t.linear.y = -kInf;
  EXPECT_EQ(TwistProblem(t), "linear.y = -inf");
}

TEST(InputChecksTest, OdometryNeedsAFinitePoseAndAUnitQuaternion) {
  nav_msgs::Odometry o = ToOdometry({1.0, 2.0, 0.5}, 0.2, 0.1, "robot_0/odom", "robot_0/base_link", ros::Time(3.0));
  EXPECT_EQ(OdometryProblem(o), "");
  EXPECT_EQ(OdometryProblem(Spoilt(o, [](auto& m) { m.pose.pose.position.x = kNan; })), "pose.pose.position.x = nan");
  // All zeros: a default-built message.
  const std::string zero = OdometryProblem(Spoilt(o, [](auto& m) { m.pose.pose.orientation = geometry_msgs::Quaternion(); }));
  EXPECT_NE(zero.find("unit quaternion"), std::string::npos) << zero;
  EXPECT_NE(OdometryProblem(Spoilt(o, [](auto& m) { m.pose.pose.orientation.z = kInf; })).find("unit quaternion"),
            std::string::npos);
  EXPECT_EQ(OdometryProblem(Spoilt(o, [](auto& m) { m.twist.twist.angular.z = kNan; })), "twist.twist.angular.z = nan");
}

TEST(InputChecksTest, RobotPosesNeedAFinitePoseForEachName) {
  multirobot_audio::RobotPoses m;
  m.names = {"robot_0", "robot_1"};
  m.poses.resize(2);
  m.poses[1].x = 3.0;
  m.poses[1].theta = -1.0;
  EXPECT_EQ(RobotPosesProblem(m), "");
  EXPECT_EQ(RobotPosesProblem(Spoilt(m, [](auto& r) { r.poses[1].theta = kNan; })), "poses[1].theta = nan");
  EXPECT_EQ(RobotPosesProblem(Spoilt(m, [](auto& r) { r.poses[0].y = kInf; })), "poses[0].y = inf");
  EXPECT_EQ(RobotPosesProblem(Spoilt(m, [](auto& r) { r.poses.pop_back(); })),
            "names and poses: one pose per name expected, got 2 names and 1 poses");
}

TEST(InputChecksTest, RobotScansNeedOneGoodScanForEachNameGivenOnce) {
  multirobot_audio::RobotScans m;
  m.names = {"robot_0", "robot_1"};
  m.scans.assign(2, ToLaserScan(std::vector<float>(16, 1.0f), Model(), "robot_0/base_link", ros::Time(1.0)));
  EXPECT_EQ(RobotScansProblem(m), "");
  EXPECT_EQ(RobotScansProblem(Spoilt(m, [](auto& r) { r.scans[1].ranges[2] = -1.0f; })),
            "scans[1] (robot_1).ranges[2] = -1");
  EXPECT_EQ(RobotScansProblem(Spoilt(m, [](auto& r) { r.scans.pop_back(); })),
            "names and scans: one scan per name expected, got 2 names and 1 scans");
  EXPECT_EQ(RobotScansProblem(Spoilt(m, [](auto& r) { r.names[1] = "robot_0"; })), "names[1] = 'robot_0': given twice");
}

TEST(InputChecksTest, RobotCommandsNeedFiniteCommandsForKnownRobotsGivenOnce) {
  multirobot_audio::RobotCommands m;
  m.names = {"robot_0", "robot_1"};
  m.commands.resize(2);
  m.commands[0].linear.x = 0.3;
  const auto known = [](const std::string& name) { return name == "robot_0" || name == "robot_1"; };
  EXPECT_EQ(RobotCommandsProblem(m, known), "");
  EXPECT_EQ(RobotCommandsProblem(Spoilt(m, [](auto& r) { r.commands[1].angular.z = kNan; }), known),
            "commands[1] (robot_1).angular.z = nan");
  EXPECT_EQ(RobotCommandsProblem(Spoilt(m, [](auto& r) { r.names[0] = "robot_9"; }), known),
            "names[0] = 'robot_9': not a robot of the world");
  EXPECT_EQ(RobotCommandsProblem(Spoilt(m, [](auto& r) { r.names.push_back("robot_2"); }), known),
            "names and commands: one command per name expected, got 3 names and 2 commands");
  EXPECT_EQ(RobotCommandsProblem(Spoilt(m, [](auto& r) { r.names[1] = "robot_0"; }), known),
            "names[1] = 'robot_0': given twice");
}

TEST(InputChecksTest, ScanTakesNanAndInfinityAsReadingsButNotNegativeRanges) {
  std::vector<float> ranges(16, 1.0f);
  ranges[3] = kInf;   // nothing in reach
  ranges[4] = kNan;   // no reading
  ranges[5] = -kInf;  // too close (REP 117)
  const sensor_msgs::LaserScan scan = ToLaserScan(ranges, Model(), "robot_0/base_link", ros::Time(1.0));
  EXPECT_EQ(ScanProblem(scan), "");
  EXPECT_EQ(ScanProblem(Spoilt(scan, [](auto& m) { m.ranges[7] = -0.5f; })), "ranges[7] = -0.5");
  EXPECT_EQ(ScanProblem(Spoilt(scan, [](auto& m) { m.angle_increment = kNan; })), "angle_increment = nan");
  EXPECT_EQ(ScanProblem(Spoilt(scan, [](auto& m) { m.range_max = 0.0f; })), "range_max = 0");
  // More readings than the angles give; one short is float rounding in a driver's angles.
  EXPECT_EQ(ScanProblem(Spoilt(scan, [](auto& m) { m.ranges.resize(40, 1.0f); })),
            "ranges: 40 readings, angle_min to angle_max gives 16");
  EXPECT_EQ(ScanProblem(Spoilt(scan, [](auto& m) { m.ranges.resize(15); })), "");
  // A robot without rangers publishes an empty scan.
  EXPECT_EQ(ScanProblem(ToLaserScan({}, Model(), "robot_0/base_link", ros::Time(1.0))), "");
}

TEST(InputChecksTest, FiducialsNeedFiniteRangeAndBearing) {
  const FiducialArray seen = ToFiducialArray({{7, 1.5, 0.2}, {9, 2.0, -1.0}}, "robot_0/base_link", ros::Time(1.0));
  EXPECT_EQ(FiducialsProblem(seen), "");
  EXPECT_EQ(FiducialsProblem(Spoilt(seen, [](auto& m) { m.fiducials[1].bearing = kNan; })), "fiducials[1].bearing = nan");
  EXPECT_EQ(FiducialsProblem(Spoilt(seen, [](auto& m) { m.fiducials[0].range = -1.0f; })), "fiducials[0].range = -1");
}

TEST(InputChecksTest, BatteryNeedsALevel) {
  world_sim::BatteryModel model;
  const sensor_msgs::BatteryState b = ToBatteryState(0.4, false, model, "robot_0/base_link", ros::Time(1.0));
  EXPECT_EQ(BatteryProblem(b), "");
  EXPECT_EQ(BatteryProblem(Spoilt(b, [](auto& m) { m.percentage = kNan; m.charge = kNan; })), "neither a percentage nor a charge and a positive capacity");
  EXPECT_NE(BatteryProblem(Spoilt(b, [](auto& m) { m.percentage = -0.2f; })).find("= -0.2"), std::string::npos) << BatteryProblem(Spoilt(b, [](auto& m) { m.percentage = -0.2f; }));
}

TEST(InputChecksTest, ReceptionTakesAnUnknownDirectionButNotANanLevel) {
  AudioReception r;
  r.kind = AudioReception::PACKET;
  r.data = {1, 2, 3, 4};
  r.level_db = 55.0f;
  r.direction = kNan;  // unknown: legitimate
  r.direction_confidence = 0.0f;
  r.quality = 1.0f;
  r.path_length = kNan;  // a real link does not know it
  EXPECT_EQ(ReceptionProblem(r), "");
  EXPECT_EQ(ReceptionProblem(Spoilt(r, [](auto& m) { m.level_db = kNan; })), "level_db = nan");
  EXPECT_EQ(ReceptionProblem(Spoilt(r, [](auto& m) { m.direction = kInf; })), "direction = inf");
  EXPECT_EQ(ReceptionProblem(Spoilt(r, [](auto& m) { m.direction_confidence = kNan; })), "direction_confidence = nan");
  EXPECT_EQ(ReceptionProblem(Spoilt(r, [](auto& m) { m.kind = 7; })), "kind = 7");
  EXPECT_EQ(ReceptionProblem(Spoilt(r, [](auto& m) { m.path_length = -3.0f; })), "path_length = -3");
  EXPECT_EQ(ReceptionProblem(Spoilt(r, [](auto& m) { m.path_length_std = -0.5f; })), "path_length_std = -0.5");
}

TEST(InputChecksTest, LockStatePacketAndJob) {
  LockState s;
  s.state = LockState::HELD;
  EXPECT_EQ(LockStateProblem(s), "");
  s.state = 9;
  EXPECT_EQ(LockStateProblem(s), "state = 9");

  AudioPacket p;
  p.data = {1, 2, 3, 4};
  EXPECT_EQ(PacketProblem(p, 4, 4), "");
  EXPECT_EQ(PacketProblem(p, 1, 255), "");
  p.data.resize(300);
  EXPECT_EQ(PacketProblem(p, 4, 4), "data: 300 bytes, the link carries 4");
  EXPECT_EQ(PacketProblem(p, 1, 255), "data: 300 bytes, the link carries 1 to 255");
  p.data.clear();
  EXPECT_EQ(PacketProblem(p, 1, 255), "data: 0 bytes, the link carries 1 to 255");

  Job j;
  j.count = 1;
  EXPECT_EQ(JobProblem(j), "");
  j.count = 0;
  EXPECT_EQ(JobProblem(j), "count = 0 (the first job is 1)");
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
