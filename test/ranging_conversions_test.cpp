// audio/teammates and its rviz markers, as nava_modem and the simulation both make them.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "ranging_ros.h"

namespace multirobot_audio {
namespace {

std::vector<ranging::TeammateView> View() {
  ranging::Range r;
  r.teammate = "robot_1";
  r.range = 2.0;
  r.range_std = 0.02;
  r.age = 1.5;
  r.samples = 3;
  ranging::TeammateView both{"robot_1", r, ranging::HeardBearing{M_PI / 2, 0.8, 0.0}, 0.5};
  ranging::Range alone = r;
  alone.teammate = "robot_2";
  alone.range = 4.0;
  ranging::TeammateView range_only{"robot_2", alone, std::nullopt, 0.0};
  ranging::TeammateView bearing_only{"robot_3", std::nullopt, ranging::HeardBearing{-1.0, 1.0, 0.0}, 2.0};
  return {both, range_only, bearing_only};
}

TEST(RangingConversions, TeammatesSayWhatIsKnownAndNaNForTheRest) {
  const Teammates msg = ToTeammatesMsg(View(), "robot_0/base_link", ros::Time(5.0));
  EXPECT_EQ(msg.header.frame_id, "robot_0/base_link");
  ASSERT_EQ(msg.teammates.size(), 3u);
  const Teammate& both = msg.teammates[0];
  EXPECT_EQ(both.name, "robot_1");
  EXPECT_FLOAT_EQ(both.range, 2.0f);
  EXPECT_FLOAT_EQ(both.range_std, 0.02f);
  EXPECT_FLOAT_EQ(both.range_age, 1.5f);
  EXPECT_EQ(both.range_samples, 3u);
  EXPECT_FLOAT_EQ(both.bearing, static_cast<float>(M_PI / 2));
  EXPECT_FLOAT_EQ(both.bearing_confidence, 0.8f);
  EXPECT_FLOAT_EQ(both.bearing_age, 0.5f);
  EXPECT_TRUE(std::isnan(msg.teammates[1].bearing));
  EXPECT_TRUE(std::isnan(msg.teammates[2].range));
  EXPECT_TRUE(std::isnan(msg.teammates[2].range_std));
  EXPECT_EQ(msg.teammates[2].range_samples, 0u);
}

TEST(RangingConversions, MarkersShowEachEstimateInTheRobotsFrame) {
  const Teammates msg = ToTeammatesMsg(View(), "robot_0/base_link", ros::Time(5.0));
  const visualization_msgs::MarkerArray m = ToTeammateMarkers({{"robot_0", msg}, {"robot_9", Teammates()}});
  ASSERT_EQ(m.markers.size(), 6u);  // clear, disc, label and line, ring, arrow
  EXPECT_EQ(m.markers[0].action, visualization_msgs::Marker::DELETEALL);
  const visualization_msgs::Marker& disc = m.markers[1];
  EXPECT_EQ(disc.type, visualization_msgs::Marker::CYLINDER);
  EXPECT_EQ(disc.ns, "robot_0");
  EXPECT_EQ(disc.header.frame_id, "robot_0/base_link");
  EXPECT_NEAR(disc.pose.position.x, 0.0, 1e-6);  // 2 m straight to the left
  EXPECT_NEAR(disc.pose.position.y, 2.0, 1e-6);
  EXPECT_NEAR(disc.scale.x, 0.1, 1e-6);          // the least width: 2 x 5 cm
  EXPECT_EQ(m.markers[2].type, visualization_msgs::Marker::TEXT_VIEW_FACING);
  EXPECT_EQ(m.markers[2].text, "robot_1 200 cm");
  EXPECT_NEAR(m.markers[2].pose.position.y, 2.0, 1e-6);
  EXPECT_NE(m.markers[1].id, m.markers[2].id);
  ASSERT_EQ(m.markers[3].points.size(), 2u);  // from the robot to the estimate
  EXPECT_NEAR(m.markers[3].points[1].y, 2.0, 1e-6);
  const visualization_msgs::Marker& ring = m.markers[4];
  EXPECT_EQ(ring.type, visualization_msgs::Marker::LINE_STRIP);
  for (const auto& p : ring.points) EXPECT_NEAR(std::hypot(p.x, p.y), 4.0, 1e-6);
  EXPECT_EQ(m.markers[5].type, visualization_msgs::Marker::ARROW);
  EXPECT_TRUE(ToTeammateMarkers({}).markers.empty());
}


// A timing names its frame by the frame's bytes, of any length a profile carries; a payload of
// no bytes or too many, a NaN arrival from a listener, or no names is refused, named.
TEST(RangingConversions, TimingsOfFramesOfAnyLengthAreTakenAndBadOnesNamed) {
  PacketTiming m;
  m.sender = "robot_0";
  m.listener = "robot_1";
  m.arrival = 1.5;
  m.data.assign(64, 7);
  EXPECT_EQ(PacketTimingProblem(m, 1, 255), "");
  m.data.assign(4, 7);
  EXPECT_EQ(PacketTimingProblem(m, 1, 255), "");
  EXPECT_EQ(PacketTimingProblem(m, 4, 4), "");
  m.data.clear();
  EXPECT_EQ(PacketTimingProblem(m, 1, 255), "data has 0 bytes, expected 1 to 255");
  m.data.assign(256, 7);
  EXPECT_EQ(PacketTimingProblem(m, 1, 255), "data has 256 bytes, expected 1 to 255");
  EXPECT_EQ(PacketTimingProblem(m, 4, 4), "data has 256 bytes, expected 4");
  m.data.assign(4, 7);
  m.arrival = std::nan("");
  EXPECT_NE(PacketTimingProblem(m, 1, 255).find("NaN only in a sender's announcement"), std::string::npos);
  m.sender.clear();
  EXPECT_EQ(PacketTimingProblem(m, 1, 255), "sender is empty");
}

}  // namespace
}  // namespace multirobot_audio
