#include "charging_conversions.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <multirobot_audio/LockState.h>

#include "conversions.h"

namespace multirobot_audio {
namespace {

using local_mutex::State;

// A behaviour that has seen charger 100 two metres ahead with a low battery: it approaches it.
charging_demo::ChargingBehaviour Approaching() {
  charging_demo::ChargingOptions options;
  options.chargers = {100};
  charging_demo::ChargingBehaviour b(options);
  charging_demo::ChargingInputs in;
  in.odom = {1.0, 0.5, 0.0};
  in.battery = 0.2;
  in.sightings = {{100, 2.0, 0.0}, {7, 1.0, 0.0}};
  in.time = 10.0;
  b.Update(in);
  return b;
}

TEST(ChargingConversions, EveryFiducialBecomesASighting) {
  multirobot_audio::FiducialArray msg;
  msg.fiducials.resize(2);
  msg.fiducials[0].id = 100;
  msg.fiducials[0].range = 2.5f;
  msg.fiducials[0].bearing = -0.5f;
  msg.fiducials[1].id = 3;
  const std::vector<charging_demo::ChargerSighting> s = ToChargerSightings(msg);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].id, 100u);
  EXPECT_DOUBLE_EQ(s[0].range, 2.5);
  EXPECT_DOUBLE_EQ(s[0].bearing, -0.5);
  EXPECT_EQ(s[1].id, 3u);
  EXPECT_TRUE(ToChargerSightings(multirobot_audio::FiducialArray()).empty());
}

TEST(ChargingConversions, LockStateValues) {
  EXPECT_EQ(FromLockStateValue(multirobot_audio::LockState::RELEASED), State::kReleased);
  EXPECT_EQ(FromLockStateValue(multirobot_audio::LockState::WANTED), State::kWanted);
  EXPECT_EQ(FromLockStateValue(multirobot_audio::LockState::SILENT), State::kSilent);
  EXPECT_EQ(FromLockStateValue(multirobot_audio::LockState::HELD), State::kHeld);
  EXPECT_FALSE(FromLockStateValue(4));
  EXPECT_FALSE(FromLockStateValue(255));
}

TEST(ChargingConversions, WorldSimsRingIsARingAndOthersAreNot) {
  world_sim::RobotModel model;
  const std::vector<float> eight(8, std::numeric_limits<float>::infinity());
  EXPECT_EQ(RingProblem(ToLaserScan(eight, model, "base_link", ros::Time(1.0))), "");

  sensor_msgs::LaserScan laser = ToLaserScan(eight, model, "base_link", ros::Time(1.0));
  laser.angle_min = static_cast<float>(-M_PI / 2);  // a front-facing laser starting on the right
  EXPECT_NE(RingProblem(laser).find("angle_min"), std::string::npos);
  laser = ToLaserScan(eight, model, "base_link", ros::Time(1.0));
  laser.angle_increment = static_cast<float>(M_PI / 8);  // half a circle
  EXPECT_NE(RingProblem(laser).find("angle_increment"), std::string::npos);
  laser = ToLaserScan(eight, model, "base_link", ros::Time(1.0));
  laser.range_max = std::numeric_limits<float>::infinity();
  EXPECT_NE(RingProblem(laser).find("range_max"), std::string::npos);
  EXPECT_NE(RingProblem(sensor_msgs::LaserScan()), "");
}

TEST(ChargingConversions, StateOfABehaviourAtRest) {
  charging_demo::ChargingOptions options;
  options.chargers = {100};
  const charging_demo::ChargingBehaviour b(options);
  const ChargingStatus status{State::kReleased, false, 0.9, false};
  const multirobot_audio::ChargingState msg = ToChargingState(b, status, 5.0, "robot_0/odom", ros::Time(5.0));
  EXPECT_EQ(msg.phase, "duty");
  EXPECT_EQ(msg.header.frame_id, "robot_0/odom");
  EXPECT_EQ(msg.header.stamp, ros::Time(5.0));
  EXPECT_DOUBLE_EQ(msg.phase_time, 5.0);
  EXPECT_EQ(msg.lock, multirobot_audio::LockState::RELEASED);
  EXPECT_FALSE(msg.want_lock);
  EXPECT_FLOAT_EQ(msg.battery, 0.9f);
  EXPECT_FALSE(msg.has_charger);
  EXPECT_EQ(msg.known_chargers, 0u);
  EXPECT_EQ(msg.charges, 0u);
  EXPECT_FALSE(msg.retracing);
}

TEST(ChargingConversions, StateNamesTheChargerInUseInTheOdomFrame) {
  const charging_demo::ChargingBehaviour b = Approaching();
  ASSERT_EQ(b.phase(), charging_demo::Phase::kApproach);
  const ChargingStatus status{State::kWanted, true, 0.2, false, true, 3};
  const multirobot_audio::ChargingState msg = ToChargingState(b, status, 12.5, "robot_1/odom", ros::Time(12.5));
  EXPECT_EQ(msg.phase, "approach");
  EXPECT_TRUE(msg.retracing);
  EXPECT_EQ(msg.retraces, 3u);
  EXPECT_DOUBLE_EQ(msg.phase_time, 2.5);
  EXPECT_EQ(msg.lock, multirobot_audio::LockState::WANTED);
  EXPECT_TRUE(msg.want_lock);
  ASSERT_TRUE(msg.has_charger);
  // Two metres straight ahead of (1, 0.5) facing +x; fiducial 7 is no charger.
  EXPECT_NEAR(msg.charger.x, 3.0, 1e-9);
  EXPECT_NEAR(msg.charger.y, 0.5, 1e-9);
  EXPECT_EQ(msg.known_chargers, 1u);
}

TEST(ChargingConversions, MarkersShowTheChargersTheWaitingRingAndALabel) {
  const charging_demo::ChargingBehaviour b = Approaching();
  const ChargingStatus status{State::kHeld, true, 0.25, false};
  const visualization_msgs::MarkerArray a =
      ToChargerMarkers(b, status, 1.0, "robot_1", {1.0, 0.5, 0.0}, "robot_1/odom", ros::Time(3.0));
  ASSERT_EQ(a.markers.size(), 5u);  // clear, the known charger, the one in use, its ring, the label
  EXPECT_EQ(a.markers[0].action, visualization_msgs::Marker::DELETEALL);
  const visualization_msgs::Marker* ring = nullptr;
  const visualization_msgs::Marker* label = nullptr;
  const visualization_msgs::Marker* in_use = nullptr;
  for (const visualization_msgs::Marker& m : a.markers) {
    if (m.ns == "waiting_ring") ring = &m;
    if (m.ns == "label") label = &m;
    if (m.ns == "in_use") in_use = &m;
  }
  ASSERT_TRUE(ring && label && in_use);
  EXPECT_EQ(in_use->header.frame_id, "robot_1/odom");
  EXPECT_NEAR(in_use->pose.position.x, 3.0, 1e-9);
  EXPECT_GT(in_use->color.g, in_use->color.r);  // green: HELD
  ASSERT_GT(ring->points.size(), 8u);
  for (const geometry_msgs::Point& p : ring->points) EXPECT_NEAR(std::hypot(p.x - 3.0, p.y - 0.5), 1.0, 1e-9);
  EXPECT_EQ(label->header.frame_id, "robot_1/odom");
  EXPECT_EQ(label->text, "robot_1: approach HELD 25%");
  EXPECT_DOUBLE_EQ(label->pose.position.x, 1.0);
  EXPECT_LT(label->pose.position.y, 0.5);  // below the robot

  // Nothing known, no charger in use: the clear and the label only.
  charging_demo::ChargingOptions options;
  options.chargers = {100};
  const visualization_msgs::MarkerArray idle = ToChargerMarkers(charging_demo::ChargingBehaviour(options), status, 1.0,
                                                                "robot_1", {0.0, 0.0, 0.0}, "robot_1/odom", ros::Time(3.0));
  ASSERT_EQ(idle.markers.size(), 2u);
  EXPECT_EQ(idle.markers[0].action, visualization_msgs::Marker::DELETEALL);
  EXPECT_EQ(idle.markers[1].ns, "label");
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
