#include "navigation_conversions.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "conversions.h"
#include "sounds_good_explorer/heard_messages.h"

namespace multirobot_audio {
namespace {

TEST(SoundsGoodConversions, LocalMapAsOccupancyGridInTheOdomFrame) {
  local_navigation::LocalMap map(local_navigation::LocalMapOptions{5, 0.5, 100.0});
  map.Recentre({1.2, -0.3});  // the robot's cell is odom cell (2, -1): the map starts at (0, -3)
  map.Set({0, 0}, local_navigation::CellState::kOccupied, 0.0);
  map.Set({1, 0}, local_navigation::CellState::kFree, 0.0);
  const nav_msgs::OccupancyGrid msg = ToOccupancyGrid(map, "robot_0/odom", ros::Time(3.0));
  EXPECT_EQ(msg.header.frame_id, "robot_0/odom");
  EXPECT_EQ(msg.info.width, 5u);
  EXPECT_EQ(msg.info.height, 5u);
  EXPECT_FLOAT_EQ(msg.info.resolution, 0.5f);
  EXPECT_DOUBLE_EQ(msg.info.origin.position.x, 0.0);
  EXPECT_DOUBLE_EQ(msg.info.origin.position.y, -1.5);
  ASSERT_EQ(msg.data.size(), 25u);
  EXPECT_EQ(msg.data[0], 100);
  EXPECT_EQ(msg.data[1], 0);
  EXPECT_EQ(msg.data[2], -1);
  // The grid's cell under the robot is the map's centre cell.
  const int i = static_cast<int>((1.2 - msg.info.origin.position.x) / 0.5);
  const int j = static_cast<int>((-0.3 - msg.info.origin.position.y) / 0.5);
  EXPECT_EQ(Eigen::Vector2i(i, j), map.centre_cell());
}

TEST(SoundsGoodConversions, PathPosesFaceTheNextPoint) {
  const nav_msgs::Path path = ToPath({{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}}, "odom", ros::Time(1.0));
  ASSERT_EQ(path.poses.size(), 3u);
  EXPECT_EQ(path.header.frame_id, "odom");
  EXPECT_NEAR(FromQuaternionYaw(path.poses[0].pose.orientation), 0.0, 1e-9);
  EXPECT_NEAR(FromQuaternionYaw(path.poses[1].pose.orientation), M_PI / 2, 1e-9);
  EXPECT_NEAR(FromQuaternionYaw(path.poses[2].pose.orientation), M_PI / 2, 1e-9);
  EXPECT_DOUBLE_EQ(path.poses[2].pose.position.y, 1.0);
  EXPECT_TRUE(ToPath({}, "odom", ros::Time(1.0)).poses.empty());
}

TEST(SoundsGoodConversions, WorldSimsRingAsRangeReadings) {
  // The scan world_sim publishes: ranger 0 ahead, counter-clockwise, nothing in reach as +inf.
  world_sim::RobotModel model;
  model.ir_count = 8;
  std::vector<float> ring(8, std::numeric_limits<float>::infinity());
  ring[0] = 0.5f;
  ring[2] = 1.0f;
  const sensor_msgs::LaserScan scan = ToLaserScan(ring, model, "robot_0/base_link", ros::Time(2.0));
  const std::vector<local_navigation::RangeReading> r = ToRangeReadings(scan);
  ASSERT_EQ(r.size(), 8u);
  for (std::size_t k = 0; k < r.size(); ++k) {
    EXPECT_NEAR(grid::NormalizeAngle(r[k].bearing - k * M_PI / 4), 0.0, 1e-6) << "ranger " << k;
  }
  EXPECT_DOUBLE_EQ(r[0].range, 0.5);
  EXPECT_DOUBLE_EQ(r[2].range, 1.0);  // to the left
  EXPECT_TRUE(std::isinf(r[1].range));
  EXPECT_TRUE(ToRangeReadings(sensor_msgs::LaserScan()).empty());
}

// The explorer reads a reception's direction from the message alone, so the real link's (a
// two-microphone pair's bit from nava_modem) and the simulated one's (audio_propagation's
// bidirectional microphone) must give it the same: the same message fields, the same score.
TEST(SoundsGoodConversions, RealAndSimulatedDirectionsReadAlike) {
  nava_modem::RxEvent real;
  real.kind = nava_modem::RxEvent::Kind::kPacket;
  real.data = {1, 2, 3, 4};
  real.level_db = -20.0;
  real.direction = M_PI;  // the pair's rear microphone heard it first
  real.direction_confidence = 0.8;
  audio_propagation::Reception simulated;
  simulated.kind = audio_propagation::Reception::Kind::kPacket;
  simulated.data = {1, 2, 3, 4};
  simulated.level_db = 55.0;
  simulated.direction = M_PI;  // a bidirectional microphone: behind
  simulated.direction_confidence = 1.0;
  const AudioReception from_real = ToAudioReception(real, "robot_0/base_link", ros::Time(2.0));
  const AudioReception from_sim = ToAudioReception(simulated, "robot_0/base_link", ros::Time(2.0));
  EXPECT_EQ(from_real.kind, from_sim.kind);
  EXPECT_EQ(from_real.data, from_sim.data);
  EXPECT_FLOAT_EQ(from_real.direction, from_sim.direction);
  EXPECT_FLOAT_EQ(from_real.direction_confidence, 0.8f);
  EXPECT_FLOAT_EQ(from_sim.direction_confidence, 1.0f);
  // The same level for both, so that only the direction is compared.
  sounds_good_explorer::HeardMessages heard_real({}), heard_sim({});
  const double yaw = 0.3;
  heard_real.Add(7, from_real.direction, yaw, 60.0, 2.0, sounds_good_explorer::ListenMode::kBidirectional);
  heard_sim.Add(7, from_sim.direction, yaw, 60.0, 2.0, sounds_good_explorer::ListenMode::kBidirectional);
  for (double cell = -M_PI; cell < M_PI; cell += 0.25) {
    EXPECT_DOUBLE_EQ(heard_real.Score(7, cell, 3.0), heard_sim.Score(7, cell, 3.0)) << cell;
  }
  EXPECT_GT(heard_real.Score(7, yaw + M_PI, 3.0), 0.0);  // behind the robot
  EXPECT_LT(heard_real.Score(7, yaw, 3.0), 0.0);         // ahead of it
  // A reception without a direction (one microphone) carries NaN and confidence 0.
  nava_modem::RxEvent mono = real;
  mono.direction = std::numeric_limits<double>::quiet_NaN();
  mono.direction_confidence = 0.0;
  const AudioReception from_mono = ToAudioReception(mono, "robot_0/base_link", ros::Time(2.0));
  EXPECT_TRUE(std::isnan(from_mono.direction));
  EXPECT_EQ(from_mono.direction_confidence, 0.0f);
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
