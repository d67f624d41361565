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
  nav_msgs::Odometry bad = o;
  bad.pose.pose.position.x = kNan;
  EXPECT_EQ(OdometryProblem(bad), "pose.pose.position.x = nan");
  bad = o;
  bad.pose.pose.orientation = geometry_msgs::Quaternion();  // all zeros: a default-built message
  bad.pose.pose.orientation.w = 0.0;
  EXPECT_NE(OdometryProblem(bad).find("unit quaternion"), std::string::npos) << OdometryProblem(bad);
  bad = o;
  bad.pose.pose.orientation.z = kInf;
  EXPECT_NE(OdometryProblem(bad).find("unit quaternion"), std::string::npos);
  bad = o;
  bad.twist.twist.angular.z = kNan;
  EXPECT_EQ(OdometryProblem(bad), "twist.twist.angular.z = nan");
}

TEST(InputChecksTest, ScanTakesNanAndInfinityAsReadingsButNotNegativeRanges) {
  std::vector<float> ranges(16, 1.0f);
  ranges[3] = kInf;   // nothing in reach
  ranges[4] = kNan;   // no reading
  ranges[5] = -kInf;  // too close (REP 117)
  const sensor_msgs::LaserScan scan = ToLaserScan(ranges, Model(), "robot_0/base_link", ros::Time(1.0));
  EXPECT_EQ(ScanProblem(scan), "");
  sensor_msgs::LaserScan bad = scan;
  bad.ranges[7] = -0.5f;
  EXPECT_EQ(ScanProblem(bad), "ranges[7] = -0.5");
  bad = scan;
  bad.angle_increment = kNan;
  EXPECT_EQ(ScanProblem(bad), "angle_increment = nan");
  bad = scan;
  bad.range_max = 0.0f;
  EXPECT_EQ(ScanProblem(bad), "range_max = 0");
  bad = scan;
  bad.ranges.resize(40, 1.0f);  // more readings than the angles give
  EXPECT_EQ(ScanProblem(bad), "ranges: 40 readings, angle_min to angle_max gives 16");
  bad = scan;
  bad.ranges.resize(15);  // one short: float rounding in a driver's angles, let through
  EXPECT_EQ(ScanProblem(bad), "");
  // A robot without rangers publishes an empty scan.
  EXPECT_EQ(ScanProblem(ToLaserScan({}, Model(), "robot_0/base_link", ros::Time(1.0))), "");
}

TEST(InputChecksTest, FiducialsNeedFiniteRangeAndBearing) {
  const FiducialArray seen = ToFiducialArray({{7, 1.5, 0.2}, {9, 2.0, -1.0}}, "robot_0/base_link", ros::Time(1.0));
  EXPECT_EQ(FiducialsProblem(seen), "");
  FiducialArray bad = seen;
  bad.fiducials[1].bearing = kNan;
  EXPECT_EQ(FiducialsProblem(bad), "fiducials[1].bearing = nan");
  bad = seen;
  bad.fiducials[0].range = -1.0f;
  EXPECT_EQ(FiducialsProblem(bad), "fiducials[0].range = -1");
}

TEST(InputChecksTest, BatteryNeedsALevel) {
  world_sim::BatteryModel model;
  const sensor_msgs::BatteryState b = ToBatteryState(0.4, false, model, "robot_0/base_link", ros::Time(1.0));
  EXPECT_EQ(BatteryProblem(b), "");
  sensor_msgs::BatteryState bad = b;
  bad.percentage = kNan;
  bad.charge = kNan;
  EXPECT_EQ(BatteryProblem(bad), "neither a percentage nor a charge and a positive capacity");
  bad = b;
  bad.percentage = -0.2f;
  EXPECT_NE(BatteryProblem(bad).find("= -0.2"), std::string::npos) << BatteryProblem(bad);
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
  AudioReception bad = r;
  bad.level_db = kNan;
  EXPECT_EQ(ReceptionProblem(bad), "level_db = nan");
  bad = r;
  bad.direction = kInf;
  EXPECT_EQ(ReceptionProblem(bad), "direction = inf");
  bad = r;
  bad.direction_confidence = kNan;
  EXPECT_EQ(ReceptionProblem(bad), "direction_confidence = nan");
  bad = r;
  bad.kind = 7;
  EXPECT_EQ(ReceptionProblem(bad), "kind = 7");
  bad = r;
  bad.path_length = -3.0f;
  EXPECT_EQ(ReceptionProblem(bad), "path_length = -3");
}

TEST(InputChecksTest, LockStatePacketAndJob) {
  LockState s;
  s.state = LockState::HELD;
  EXPECT_EQ(LockStateProblem(s), "");
  s.state = 9;
  EXPECT_EQ(LockStateProblem(s), "state = 9");

  AudioPacket p;
  p.data = {1, 2, 3, 4};
  EXPECT_EQ(PacketProblem(p, 4), "");
  p.data.resize(300);
  EXPECT_EQ(PacketProblem(p, 4), "data: 300 bytes, the link carries 4");

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
