#include "sounds_good_explorer/marker_packet.h"
#include "sounds_good_explorer/transport_task.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace sounds_good_explorer {
namespace {

TEST(MarkerPacket, RoundTripsAndRejectsOthers) {
  const auto packet = EncodeMarkerPacket(0x1234);
  EXPECT_EQ(packet[0], 'S');
  EXPECT_EQ(packet[1], 'G');
  EXPECT_EQ(packet[2], 0x12);
  EXPECT_EQ(packet[3], 0x34);
  EXPECT_EQ(DecodeMarkerPacket({packet.begin(), packet.end()}), 0x1234u);
  EXPECT_FALSE(DecodeMarkerPacket({11, 'R', 0, 3}));    // a local mutex request
  EXPECT_FALSE(DecodeMarkerPacket({'S', 'G', 1}));      // wrong size
  EXPECT_THROW(EncodeMarkerPacket(70000), std::invalid_argument);
}

TaskOptions Options() {
  TaskOptions o;
  o.source = 7;
  o.sink = 9;
  return o;
}

TEST(TransportTask, SeeksTheSourceWorksThereThenSeeksTheSink) {
  TransportTask task(Options());
  EXPECT_EQ(task.sought(), 7u);
  task.Seen(9, {5.0, 0.0}, 1.0);  // the sink, not sought yet
  EXPECT_FALSE(task.Update({4.9, 0.0}, 1.0));
  EXPECT_FALSE(task.working());
  task.Seen(7, {2.0, 0.0}, 2.0);
  ASSERT_TRUE(task.SoughtPosition(2.0));
  EXPECT_FALSE(task.Update({1.0, 0.0}, 2.0));  // 1 m away: not there yet
  EXPECT_FALSE(task.working());
  EXPECT_FALSE(task.Update({1.5, 0.0}, 3.0));  // within 0.6 m
  EXPECT_TRUE(task.working());
  EXPECT_FALSE(task.Update({1.5, 0.0}, 32.9));
  const auto job = task.Update({1.5, 0.0}, 33.0);
  ASSERT_TRUE(job);
  EXPECT_EQ(job->count, 1);
  EXPECT_EQ(job->marker, 7u);
  EXPECT_DOUBLE_EQ(job->time, 33.0);
  EXPECT_EQ(task.sought(), 9u);
  EXPECT_FALSE(task.working());
  EXPECT_FALSE(task.SoughtPosition(33.0));  // the sink sighting is 32 s old
}

TEST(TransportTask, ASightingGuidesOnlyForTheMarkerMemory) {
  TransportTask task(Options());
  task.Seen(7, {2.0, 0.0}, 10.0);
  EXPECT_TRUE(task.SoughtPosition(15.0));
  EXPECT_FALSE(task.SoughtPosition(15.1));
  EXPECT_FALSE(task.Update({2.0, 0.0}, 15.1));
  EXPECT_FALSE(task.working());
}

TEST(TransportTask, AnnouncesMarkersSeenInTheLastTenSecondsEveryPeriod) {
  TransportTask task(Options());
  EXPECT_TRUE(task.DueAnnouncements(0.0).empty());
  task.Seen(7, {2.0, 0.0}, 1.0);
  task.Seen(9, {3.0, 0.0}, 1.5);
  EXPECT_EQ(task.DueAnnouncements(1.5), (std::vector<std::uint32_t>{7, 9}));
  EXPECT_TRUE(task.DueAnnouncements(2.0).empty());  // announced 0.5 s ago
  EXPECT_EQ(task.DueAnnouncements(3.5).size(), 2u);
  EXPECT_EQ(task.DueAnnouncements(11.0), (std::vector<std::uint32_t>{7, 9}));
  EXPECT_EQ(task.DueAnnouncements(11.4), std::vector<std::uint32_t>{});
  EXPECT_EQ(task.DueAnnouncements(13.0), std::vector<std::uint32_t>{});  // both out of the window
}

TEST(TransportTask, RejectsImpossibleOptions) {
  TaskOptions o = Options();
  o.sink = o.source;
  EXPECT_THROW(TransportTask{o}, std::invalid_argument);
  o = Options();
  o.arrive_radius = 0.0;
  EXPECT_THROW(TransportTask{o}, std::invalid_argument);
}

}  // namespace
}  // namespace sounds_good_explorer
