#include "conversions.h"
#include "rviz_markers.h"

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace multirobot_audio {
namespace {

TEST(Conversions, YawQuaternionRoundTrips) {
  for (double yaw : {0.0, 0.5, -2.0, M_PI - 1e-9}) {
    EXPECT_NEAR(FromQuaternionYaw(ToYawQuaternion(yaw)), yaw, 1e-9);
  }
}

TEST(Conversions, OccupancyGridRoundTrips) {
  grid::OccupancyMap map(3, 2, 0.25, {1.0, -1.0, 0.3});
  map.set(0, 0, grid::Cell::kOccupied);
  map.set(2, 1, grid::Cell::kUnknown);
  const nav_msgs::OccupancyGrid msg = ToOccupancyGrid(map, "map", ros::Time(5.0));
  EXPECT_EQ(msg.header.frame_id, "map");
  EXPECT_EQ(msg.info.width, 3u);
  EXPECT_EQ(msg.info.height, 2u);
  ASSERT_EQ(msg.data.size(), 6u);
  EXPECT_EQ(msg.data[0], 100);
  EXPECT_EQ(msg.data[1], 0);
  EXPECT_EQ(msg.data[5], -1);
  const grid::OccupancyMap back = FromOccupancyGrid(msg);
  EXPECT_EQ(back.cells(), map.cells());
  EXPECT_NEAR(back.origin().yaw, 0.3, 1e-6);
  EXPECT_NEAR(back.resolution(), 0.25, 1e-6);
}

TEST(Conversions, OccupancyGridOfTheWrongSizeIsRejected) {
  nav_msgs::OccupancyGrid msg;
  msg.info.width = 2;
  msg.info.height = 2;
  msg.info.resolution = 1.0f;
  msg.info.origin.orientation.w = 1.0;
  msg.data.assign(3, 0);
  EXPECT_THROW(FromOccupancyGrid(msg), std::invalid_argument);
}

TEST(Conversions, LaserScanOfARing) {
  world_sim::RobotModel model;
  const std::vector<float> ranges(8, 1.0f);
  const sensor_msgs::LaserScan s = ToLaserScan(ranges, model, "robot_0/base_link", ros::Time(2.0));
  EXPECT_FLOAT_EQ(s.angle_min, 0.0f);
  EXPECT_FLOAT_EQ(s.angle_increment, static_cast<float>(M_PI / 4));
  EXPECT_FLOAT_EQ(s.angle_max, static_cast<float>(7 * M_PI / 4));
  EXPECT_FLOAT_EQ(s.range_max, static_cast<float>(model.radius + model.ir_range));
  EXPECT_EQ(s.ranges.size(), 8u);
}

TEST(Conversions, OdometryAndTransform) {
  const nav_msgs::Odometry o = ToOdometry({1.0, 2.0, 0.5}, 0.2, -0.1, "odom", "base", ros::Time(3.0));
  EXPECT_EQ(o.child_frame_id, "base");
  EXPECT_DOUBLE_EQ(o.pose.pose.position.y, 2.0);
  EXPECT_NEAR(FromQuaternionYaw(o.pose.pose.orientation), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(o.twist.twist.angular.z, -0.1);
  const auto t = ToTransform({1.0, 2.0, 0.5}, "map", "odom", ros::Time(3.0));
  EXPECT_EQ(t.child_frame_id, "odom");
  EXPECT_DOUBLE_EQ(t.transform.translation.x, 1.0);
}

TEST(Conversions, BatteryStatus) {
  const world_sim::BatteryModel m;
  EXPECT_EQ(ToBatteryState(0.5, false, m, "b", ros::Time(1.0)).power_supply_status,
            sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_DISCHARGING);
  EXPECT_EQ(ToBatteryState(0.5, true, m, "b", ros::Time(1.0)).power_supply_status,
            sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_CHARGING);
  const auto full = ToBatteryState(1.0, true, m, "b", ros::Time(1.0));
  EXPECT_EQ(full.power_supply_status, sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_FULL);
  EXPECT_FLOAT_EQ(full.voltage, static_cast<float>(m.full_voltage));
}

TEST(Conversions, BatteryReadingUndoesWorldSimsBatteryState) {
  const world_sim::BatteryModel m;
  for (const bool docked : {false, true}) {
    for (const double level : {0.0, 0.31, 1.0}) {
      const BatteryReading r = FromBatteryState(ToBatteryState(level, docked, m, "b", ros::Time(1.0)));
      EXPECT_NEAR(r.level, level, 1e-6);
      EXPECT_EQ(r.docked, docked) << "level " << level;
    }
  }
}

TEST(Conversions, BatteryReadingFromChargeWithoutPercentage) {
  sensor_msgs::BatteryState msg;
  msg.percentage = std::numeric_limits<float>::quiet_NaN();
  msg.charge = 1.5f;
  msg.capacity = 3.0f;
  msg.power_supply_status = sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_NOT_CHARGING;
  const BatteryReading r = FromBatteryState(msg);
  EXPECT_NEAR(r.level, 0.5, 1e-9);
  EXPECT_FALSE(r.docked);
  msg.capacity = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(FromBatteryState(msg).level));
}

TEST(Conversions, PoseInThePlane) {
  geometry_msgs::Pose pose;
  pose.position.x = 1.5;
  pose.position.y = -2.0;
  pose.position.z = 0.3;
  pose.orientation = ToYawQuaternion(2.5);
  const grid::Pose2D p = FromPose(pose);
  EXPECT_DOUBLE_EQ(p.x, 1.5);
  EXPECT_DOUBLE_EQ(p.y, -2.0);
  EXPECT_NEAR(p.yaw, 2.5, 1e-12);
}

TEST(Conversions, FiducialArray) {
  const auto msg = ToFiducialArray({{4u, 2.0, 0.5}}, "cam", ros::Time(1.0));
  ASSERT_EQ(msg.fiducials.size(), 1u);
  EXPECT_EQ(msg.fiducials[0].id, 4u);
  EXPECT_FLOAT_EQ(msg.fiducials[0].bearing, 0.5f);
}

TEST(Conversions, DirectionArrowPointsWhereTheSoundCameFrom) {
  const visualization_msgs::Marker m = ToDirectionMarker(M_PI / 2.0, 1.0, true, "robot_3/base_link", ros::Time(4.0), 7);
  EXPECT_EQ(m.header.frame_id, "robot_3/base_link");
  EXPECT_EQ(m.type, visualization_msgs::Marker::ARROW);
  EXPECT_EQ(m.id, 7);
  ASSERT_EQ(m.points.size(), 2u);
  EXPECT_NEAR(m.points[1].x, 0.0, 1e-9);  // to the left, 1 m at full confidence
  EXPECT_NEAR(m.points[1].y, 1.0, 1e-9);
  const visualization_msgs::Marker unsure = ToDirectionMarker(M_PI, 0.0, false, "robot_3/base_link", ros::Time(4.0), 8);
  EXPECT_NEAR(unsure.points[1].x, -0.3, 1e-9);  // behind, short
  EXPECT_GT(unsure.color.r, unsure.color.g);    // noise is drawn orange
}

// Each noise class in the message's own constants: a simulated collision (the threshold model
// reports no class), the acoustic model's and the real receiver's classes; a packet has none.
TEST(Conversions, ReceptionsCarryTheirNoiseClass) {
  using multirobot_audio::AudioReception;
  audio_propagation::Reception sim;
  sim.kind = audio_propagation::Reception::Kind::kNoise;
  sim.data = {9};
  EXPECT_EQ(ToAudioReception(sim, "f", ros::Time(1.0)).noise, AudioReception::COLLISION);
  EXPECT_EQ(ToAudioReception(sim, "f", ros::Time(1.0)).kind, AudioReception::NOISE);
  EXPECT_TRUE(ToAudioReception(sim, "f", ros::Time(1.0)).data.empty());
  sim.noise = nava_modem::RxEvent::Noise::kOneByte;
  EXPECT_EQ(ToAudioReception(sim, "f", ros::Time(1.0)).noise, AudioReception::ONE_BYTE);
  sim.kind = audio_propagation::Reception::Kind::kPacket;
  sim.noise = nava_modem::RxEvent::Noise::kNone;
  const AudioReception packet = ToAudioReception(sim, "f", ros::Time(1.0));
  EXPECT_EQ(packet.kind, AudioReception::PACKET);
  EXPECT_EQ(packet.noise, AudioReception::NONE);
  EXPECT_EQ(packet.data, std::vector<std::uint8_t>{9});
  nava_modem::RxEvent real;
  real.kind = nava_modem::RxEvent::Kind::kNoise;
  real.noise = nava_modem::RxEvent::Noise::kZeroByte;
  EXPECT_EQ(ToAudioReception(real, "f", ros::Time(1.0)).noise, AudioReception::ZERO_BYTE);
  real.noise = nava_modem::RxEvent::Noise::kBadCrc;
  EXPECT_EQ(ToAudioReception(real, "f", ros::Time(1.0)).noise, AudioReception::BAD_CRC);
}

// A path that sounds at `level_db` along `points`.
audio_propagation::SoundPath PathAt(double level_db, bool audible, std::vector<Eigen::Vector2d> points) {
  audio_propagation::SoundPath p;
  p.reachable = true;
  p.audible = audible;
  p.level_db = level_db;
  p.polyline = std::move(points);
  return p;
}

TEST(Conversions, SoundPathsOneMarkerPerPathHeard) {
  const std::vector<std::string> robots = {"robot_0", "robot_1", "robot_2"};
  audio_propagation::PropagationOptions levels;  // 70 dB at the source, 40 dB the quietest heard
  audio_propagation::Transmission tx;
  tx.sender = 1;
  tx.duration = 0.4;
  tx.paths = {PathAt(70.0, true, {{0.0, 0.0}, {1.0, 0.0}, {1.0, 2.0}}), audio_propagation::SoundPath(),
              PathAt(40.0, true, {{0.0, 0.0}, {3.0, 0.0}})};
  audio_propagation::Transmission faint = tx;
  faint.sender = 2;
  faint.paths = {PathAt(30.0, false, {{0.0, 0.0}, {5.0, 0.0}}), PathAt(50.0, true, {{0.0, 0.0}, {0.0, 1.0}}),
                 audio_propagation::SoundPath()};

  const visualization_msgs::MarkerArray a =
      ToSoundPathMarkers({tx, faint}, robots, levels, 2.0, "world", ros::Time(5.0), 40);
  ASSERT_EQ(a.markers.size(), 3u);  // the unheard and unreachable paths are not drawn
  for (std::size_t k = 0; k < a.markers.size(); ++k) {
    const visualization_msgs::Marker& m = a.markers[k];
    EXPECT_EQ(m.header.frame_id, "world");
    EXPECT_EQ(m.header.stamp, ros::Time(5.0));
    EXPECT_EQ(m.type, visualization_msgs::Marker::LINE_STRIP);
    EXPECT_EQ(m.id, 40 + static_cast<int>(k));
    EXPECT_DOUBLE_EQ(m.lifetime.toSec(), 2.0);  // the display time, longer than the packet
  }
  EXPECT_EQ(a.markers[0].ns, "robot_1");
  EXPECT_EQ(a.markers[2].ns, "robot_2");
  ASSERT_EQ(a.markers[0].points.size(), 3u);
  EXPECT_DOUBLE_EQ(a.markers[0].points[2].y, 2.0);
  EXPECT_DOUBLE_EQ(a.markers[0].points[2].z, 0.15);
  EXPECT_FLOAT_EQ(a.markers[0].color.r, 1.0f);  // at the source level: red
  EXPECT_FLOAT_EQ(a.markers[0].color.b, 0.0f);
  EXPECT_FLOAT_EQ(a.markers[1].color.r, 0.0f);  // at the threshold: blue
  EXPECT_FLOAT_EQ(a.markers[1].color.b, 1.0f);

  // A packet longer than the display time lasts as long as it sounds.
  EXPECT_DOUBLE_EQ(ToSoundPathMarkers({tx}, robots, levels, 0.0, "map", ros::Time(5.0), 0).markers[0].lifetime.toSec(),
                   0.4);
  EXPECT_TRUE(ToSoundPathMarkers({}, robots, levels, 0.0, "map", ros::Time(5.0), 0).markers.empty());
}

TEST(Conversions, SoundPathsOfTheAcousticModelByDecodeChance) {
  audio_propagation::Transmission tx;
  tx.sender = 0;
  tx.paths = {audio_propagation::SoundPath(), PathAt(20.0, false, {{0.0, 0.0}, {1.0, 1.0}}),
              PathAt(60.0, true, {{0.0, 0.0}, {2.0, 0.0}})};
  tx.probability = {0.0, 1.0, 0.005};  // the threshold model's `audible` plays no part
  const visualization_msgs::MarkerArray a =
      ToSoundPathMarkers({tx}, {"robot_0", "robot_1", "robot_2"}, {}, 0.0, "map", ros::Time(1.0), 0);
  ASSERT_EQ(a.markers.size(), 1u);
  EXPECT_EQ(a.markers[0].header.frame_id, "map");
  EXPECT_FLOAT_EQ(a.markers[0].color.g, 1.0f);  // sure to be decoded: green
  EXPECT_FLOAT_EQ(a.markers[0].color.r, 0.0f);
  EXPECT_DOUBLE_EQ(a.markers[0].points[1].x, 1.0);
}

TEST(Conversions, DiffractionPointsAsOneMarkerInTheFrameGiven) {
  const visualization_msgs::MarkerArray a = ToDiffractionPointMarkers({{1.0, 2.0}, {3.0, 4.0}}, "world");
  ASSERT_EQ(a.markers.size(), 1u);
  const visualization_msgs::Marker& m = a.markers[0];
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.ns, "corners");
  EXPECT_EQ(m.type, visualization_msgs::Marker::POINTS);
  ASSERT_EQ(m.points.size(), 2u);
  EXPECT_DOUBLE_EQ(m.points[1].x, 3.0);
  EXPECT_DOUBLE_EQ(m.points[1].y, 4.0);
  EXPECT_TRUE(ToDiffractionPointMarkers({}, "map").markers[0].points.empty());
}

TEST(Conversions, RoomsAsFloorsNamesAndOpenings) {
  // Two 4 x 3 m rooms joined by a 1 m door (x = 4.0 .. 4.1 wall, door y = 1 .. 2), 0.1 m cells.
  grid::OccupancyMap map(81, 30, 0.1);
  for (int j = 0; j < 30; ++j) {
    if (j >= 10 && j < 20) continue;
    map.set(40, j, grid::Cell::kOccupied);
  }
  world_sim::Acoustics acoustics;
  acoustics.room.rt60 = 0.7;
  acoustics.room.volume = 100.0;
  acoustics.rooms = world_sim::CoupledRoomsSpec{};
  const audio_propagation::RoomCoupling rooms(map, acoustics);
  ASSERT_EQ(rooms.segmentation().rooms().size(), 2u);
  const visualization_msgs::MarkerArray a = ToRoomMarkers(rooms, map, "world");
  ASSERT_EQ(a.markers.size(), 1u + 2u + 1u);
  const visualization_msgs::Marker& floors = a.markers[0];
  EXPECT_EQ(floors.ns, "room_floors");
  EXPECT_EQ(floors.header.frame_id, "world");
  EXPECT_EQ(floors.type, visualization_msgs::Marker::CUBE_LIST);
  EXPECT_DOUBLE_EQ(floors.scale.x, 0.3);  // three cells of 0.1 m: at least 0.25 m
  ASSERT_EQ(floors.points.size(), floors.colors.size());
  EXPECT_GT(floors.points.size(), 100u);
  // The two rooms in different colours.
  bool two_colours = false;
  for (const std_msgs::ColorRGBA& c : floors.colors) {
    two_colours |= c.r != floors.colors[0].r || c.g != floors.colors[0].g || c.b != floors.colors[0].b;
  }
  EXPECT_TRUE(two_colours);
  EXPECT_EQ(a.markers[1].ns, "room_names");
  EXPECT_NE(a.markers[1].text.find("RT60 0.70 s"), std::string::npos) << a.markers[1].text;
  const visualization_msgs::Marker& door = a.markers[3];
  EXPECT_EQ(door.ns, "openings");
  EXPECT_NEAR(door.pose.position.x, 4.05, 0.2);
  EXPECT_NEAR(door.pose.position.y, 1.5, 0.2);
  EXPECT_NEAR(door.scale.x, 1.0, 0.25);
}

}  // namespace
}  // namespace multirobot_audio

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
