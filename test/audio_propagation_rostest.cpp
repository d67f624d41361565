// rostest for the audio_propagation node (test/audio_propagation.test).
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <multirobot_audio/AudioPacket.h>
#include <multirobot_audio/AudioReception.h>
#include <multirobot_audio/CarrierSense.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "wait_for.h"

namespace {

using multirobot_audio::AudioReception;

using multirobot_audio::testing::WaitFor;

TEST(AudioPropagationNode, APacketReachesTheRobotsThatCanHearIt) {
  ros::NodeHandle nh;
  std::map<int, std::vector<AudioReception>> heard;
  std::vector<ros::Subscriber> subs;
  bool carrier_at_1 = false;
  for (int k = 0; k < 4; ++k) {
    subs.push_back(nh.subscribe<AudioReception>("/robot_" + std::to_string(k) + "/audio/rx", 10,
                                                [&heard, k](const AudioReception::ConstPtr& m) { heard[k].push_back(*m); }));
  }
  auto carrier = nh.subscribe<multirobot_audio::CarrierSense>(
      "/robot_1/audio/carrier", 100, [&](const multirobot_audio::CarrierSense::ConstPtr& m) { carrier_at_1 |= m->carrier; });
  std::size_t path_markers = 0;
  auto paths = nh.subscribe<visualization_msgs::MarkerArray>(
      "/audio_propagation/paths", 10, [&](const visualization_msgs::MarkerArray::ConstPtr& m) { path_markers += m->markers.size(); });
  auto tx = nh.advertise<multirobot_audio::AudioPacket>("/robot_0/audio/tx", 10);
  ASSERT_TRUE(WaitFor([&] { return tx.getNumSubscribers() > 0 && paths.getNumPublishers() > 0; }, 60.0));
  ros::WallDuration(1.0).sleep();  // let the node read every robot's pose

  multirobot_audio::AudioPacket packet;
  packet.data = {1, 2, 3, 4};
  tx.publish(packet);
  ASSERT_TRUE(WaitFor([&] { return heard[1].size() >= 1 && heard[2].size() >= 1; }, 30.0));
  WaitFor([] { return false; }, 1.0);  // anything else that would arrive

  ASSERT_EQ(heard[1].size(), 1u);
  const AudioReception& near = heard[1][0];
  EXPECT_EQ(near.kind, AudioReception::PACKET);
  EXPECT_EQ(near.data, std::vector<std::uint8_t>({1, 2, 3, 4}));
  EXPECT_NEAR(near.path_length, 2.0, 1e-4);
  EXPECT_NEAR(near.level_db, 70.0 - 20.0 * std::log10(2.0), 1e-3);
  EXPECT_NEAR(near.direction, -M_PI / 2, 1e-3);  // robot_0 is straight to its right
  EXPECT_EQ(near.header.frame_id, "robot_1/base_link");

  ASSERT_EQ(heard[2].size(), 1u);
  const AudioReception& behind = heard[2][0];
  EXPECT_EQ(behind.kind, AudioReception::PACKET);
  const double around = std::hypot(1.5, 1.5) + 0.15 + std::hypot(1.05, 0.5);
  EXPECT_NEAR(behind.path_length, around, 1e-3);
  EXPECT_NEAR(behind.level_db, 70.0 - 20.0 * std::log10(around), 1e-3);
  EXPECT_NEAR(behind.direction, std::atan2(0.5, -1.05), 1e-3);  // from the wall's corner

  EXPECT_TRUE(heard[3].empty()) << "robot_3 is beyond hearing range";
  EXPECT_TRUE(heard[0].empty()) << "a robot does not hear itself";
  EXPECT_TRUE(carrier_at_1);
  EXPECT_EQ(path_markers, 2u);  // one per heard path
}

// A frame of the length and rate the test is given (~frame_bytes, ~rate: 4 and 0 unless its
// launch file runs the node on the room profile at a faster rate) reaches robot_1 whole, with its
// rate, after its own airtime.
TEST(AudioPropagationNode, AFrameArrivesWholeWithItsRate) {
  ros::NodeHandle nh, pnh("~");
  const int bytes = pnh.param("frame_bytes", 4), rate = pnh.param("rate", 0);
  std::vector<AudioReception> heard;
  auto sub = nh.subscribe<AudioReception>("/robot_1/audio/rx", 10, [&](const AudioReception::ConstPtr& m) { heard.push_back(*m); });
  auto tx = nh.advertise<multirobot_audio::AudioPacket>("/robot_0/audio/tx", 10);
  ASSERT_TRUE(WaitFor([&] { return tx.getNumSubscribers() > 0 && sub.getNumPublishers() > 0; }, 30.0));
  multirobot_audio::AudioPacket frame;
  for (int k = 0; k < bytes; ++k) frame.data.push_back(static_cast<std::uint8_t>(11 * k + 3));
  const ros::Time sent = ros::Time::now();
  tx.publish(frame);
  ASSERT_TRUE(WaitFor([&] { return !heard.empty(); }, 60.0)) << "robot_1 heard nothing of a " << bytes << "-byte frame";
  EXPECT_EQ(heard[0].kind, AudioReception::PACKET);
  EXPECT_EQ(heard[0].data, frame.data);
  EXPECT_EQ(static_cast<int>(heard[0].rate), rate);
  std::printf("audio_propagation_rostest: a %d-byte frame at rate %d heard %.2f s (simulated) after it was sent\n", bytes,
              rate, (heard[0].header.stamp - sent).toSec());
}

TEST(AudioPropagationNode, PacketsOfTheWrongSizeAreRejected) {
  ros::NodeHandle nh;
  std::size_t heard = 0;
  auto sub = nh.subscribe<AudioReception>("/robot_1/audio/rx", 10, [&](const AudioReception::ConstPtr&) { ++heard; });
  auto tx = nh.advertise<multirobot_audio::AudioPacket>("/robot_0/audio/tx", 10);
  ASSERT_TRUE(WaitFor([&] { return tx.getNumSubscribers() > 0; }, 30.0));
  multirobot_audio::AudioPacket empty, big;
  big.data.assign(300, 7);  // more than any profile carries
  tx.publish(empty);
  tx.publish(big);
  WaitFor([] { return false; }, 2.0);
  EXPECT_EQ(heard, 0u);
}

// In a world of coupled rooms (test/audio_propagation_rooms.test gives ~rooms and ~openings, the
// counts its world's map is cut into) the node draws them, latched: a floor of coloured squares,
// a name a room and a disc a door. The other launch files' worlds have no rooms: skipped there.
TEST(AudioPropagationNode, TheRoomsAreDrawn) {
  ros::NodeHandle nh, pnh("~");
  const int rooms = pnh.param("rooms", 0), openings = pnh.param("openings", 0);
  if (rooms == 0) GTEST_SKIP() << "this launch file's world has no coupled rooms";
  std::vector<visualization_msgs::MarkerArray> got;
  auto sub = nh.subscribe<visualization_msgs::MarkerArray>(
      "/audio_propagation/rooms", 1, [&](const visualization_msgs::MarkerArray::ConstPtr& m) { got.push_back(*m); });
  ASSERT_TRUE(WaitFor([&] { return !got.empty(); }, 60.0)) << "no ~rooms markers";
  std::map<std::string, int> by_namespace;
  for (const visualization_msgs::Marker& m : got[0].markers) ++by_namespace[m.ns];
  EXPECT_EQ(by_namespace["room_floors"], 1);
  EXPECT_EQ(by_namespace["room_names"], rooms);
  EXPECT_EQ(by_namespace["openings"], openings);
  EXPECT_GT(got[0].markers[0].points.size(), 1000u);  // the office's floor in 0.25 m squares
}

}  // namespace
