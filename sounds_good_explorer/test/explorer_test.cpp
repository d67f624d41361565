#include "sounds_good_explorer/explorer.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "sounds_good_explorer/marker_packet.h"

namespace sounds_good_explorer {
namespace {

using local_navigation::RangeReading;

const double kNothing = std::numeric_limits<double>::infinity();

// Eight rangers seeing nothing: open floor all round.
std::vector<RangeReading> OpenFloor() {
  std::vector<RangeReading> r;
  for (int k = 0; k < 8; ++k) r.push_back({k * M_PI / 4.0, kNothing});
  return r;
}

Explorer Robot(ListenMode mode = ListenMode::kBidirectional) {
  ExplorerOptions o;
  o.mode = mode;
  o.task.work_time = 5.0;
  return Explorer(o);
}

TEST(Explorer, DrivesToASeenMarkerWorksThereAndAnnouncesIt) {
  Explorer robot = Robot();
  robot.OnOdometry({0.0, 0.0, 0.0}, 0.0);
  robot.OnRanges(OpenFloor(), 1.575, 0.0);
  robot.OnSightings({{1, 2.0, 0.0}}, 0.0);  // the source, 2 m ahead
  ExplorerOutput out = robot.Update(0.0);
  EXPECT_TRUE(robot.goal_is_marker());
  EXPECT_GT(out.v, 0.0);
  EXPECT_LT(std::abs(out.w), 1.0);  // roughly ahead (the plan runs on 4-connected cells)
  ASSERT_EQ(out.packets.size(), 1u);
  EXPECT_EQ(out.packets[0], EncodeMarkerPacket(1));
  EXPECT_TRUE(robot.Update(1.0).packets.empty());  // next announcement after the period
  EXPECT_EQ(robot.Update(2.0).packets.size(), 1u);
  // Arrive within the radius: the robot stops and works.
  robot.OnOdometry({1.5, 0.0, 0.0}, 3.0);
  out = robot.Update(3.0);
  EXPECT_TRUE(robot.task().working());
  EXPECT_EQ(out.v, 0.0);
  EXPECT_EQ(out.w, 0.0);
  out = robot.Update(8.0);  // 5 s of work
  ASSERT_TRUE(out.job);
  EXPECT_EQ(out.job->marker, 1u);
  EXPECT_EQ(robot.task().sought(), 2u);
  // Announcements stop 10 s after the last sighting.
  EXPECT_EQ(robot.Update(10.0).packets.size(), 1u);
  EXPECT_TRUE(robot.Update(12.0).packets.empty());
}

TEST(Explorer, TurnsTowardAHeardAnnouncementOfTheSoughtMarker) {
  for (double heard : {M_PI / 2, -M_PI / 2}) {
    Explorer robot = Robot(ListenMode::kOmni);
    robot.OnOdometry({0.0, 0.0, 0.0}, 0.0);
    robot.OnRanges(OpenFloor(), 1.575, 0.0);
    const auto packet = EncodeMarkerPacket(1);
    for (int k = 0; k < 5; ++k) robot.OnHeard({packet.begin(), packet.end()}, 70.0, heard, 0.0);
    robot.Update(0.0);
    ASSERT_TRUE(robot.goal());
    // The goal lies on the side the sound came from.
    EXPECT_GT(robot.goal()->y() * std::sin(heard), 0.5) << heard;
  }
}

TEST(Explorer, IgnoresForeignPacketsAndAnnouncementsOfOtherMarkersInItsChoice) {
  Explorer robot = Robot(ListenMode::kOmni);
  robot.OnOdometry({0.0, 0.0, 0.0}, 0.0);
  robot.OnHeard({11, 'R', 0, 3}, 70.0, 0.0, 0.0);  // a local mutex request
  robot.OnHeard({'S', 'G', 0}, 70.0, 0.0, 0.0);     // too short
  EXPECT_EQ(robot.foreign_packets(), 2u);
  const auto sink = EncodeMarkerPacket(2);
  robot.OnHeard({sink.begin(), sink.end()}, 70.0, 0.0, 0.0);
  EXPECT_EQ(robot.heard().messages().size(), 1u);
  EXPECT_EQ(robot.heard().Score(1, 0.0, 0.0), 0.0);  // it seeks the source
}

TEST(Explorer, NoneModeKeepsNoMessages) {
  Explorer robot = Robot(ListenMode::kNone);
  robot.OnOdometry({0.0, 0.0, 0.0}, 0.0);
  const auto packet = EncodeMarkerPacket(1);
  robot.OnHeard({packet.begin(), packet.end()}, 70.0, 0.0, 0.0);
  EXPECT_TRUE(robot.heard().messages().empty());
  EXPECT_EQ(robot.foreign_packets(), 0u);
}

TEST(Explorer, BacksOffWhenItCannotMove) {
  Explorer robot = Robot();
  robot.OnOdometry({0.0, 0.0, 0.0}, 0.0);
  robot.OnRanges(OpenFloor(), 1.575, 0.0);
  robot.OnSightings({{1, 3.0, 0.0}}, 0.0);
  for (double t = 0.0; t <= 4.5; t += 0.1) {
    robot.OnSightings({{1, 3.0, 0.0}}, t);
    robot.Update(t);  // the odometry never moves: something holds the robot
  }
  EXPECT_EQ(robot.stuck_count(), 1u);
  robot.OnSightings({{1, 3.0, 0.0}}, 4.6);
  EXPECT_LT(robot.Update(4.6).v, 0.0);  // reversing
}

TEST(Explorer, RejectsImpossibleOptions) {
  ExplorerOptions o;
  o.motion.max_speed = 0.0;
  EXPECT_THROW(Explorer{o}, std::invalid_argument);
  o = ExplorerOptions();
  o.task.source = 70000;
  EXPECT_THROW(Explorer{o}, std::invalid_argument);
}

}  // namespace
}  // namespace sounds_good_explorer
