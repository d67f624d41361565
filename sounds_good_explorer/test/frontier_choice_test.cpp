#include "sounds_good_explorer/frontier_choice.h"
#include "sounds_good_explorer/frontiers.h"
#include "sounds_good_explorer/heard_messages.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sounds_good_explorer {
namespace {

using local_navigation::CellState;
using local_navigation::LocalMap;
using local_navigation::LocalMapOptions;

// A known-free disc of radius 3 m around the robot at the origin, unknown beyond: the
// frontiers form a ring, every direction equally near.
LocalMap Disc() {
  LocalMap map(LocalMapOptions{41, 0.2, 1000.0});
  map.Recentre({0.0, 0.0});
  for (int y = 0; y < 41; ++y)
    for (int x = 0; x < 41; ++x)
      if (map.CentreOf({x, y}).norm() <= 3.0) map.Set({x, y}, CellState::kFree, 0.0);
  return map;
}

double Bearing(const LocalMap& map, const Eigen::Vector2i& cell) {
  const Eigen::Vector2d p = map.CentreOf(cell);
  return std::atan2(p.y(), p.x());
}

FrontierOptions Options(double noise = 0.05) {
  FrontierOptions o;
  o.noise_std = noise;
  o.audio_weight = 3.0;
  o.min_distance = 1.0;
  return o;
}

TEST(HeardMessages, ScoreIsAgreementTimesFreshnessTimesLoudness) {
  HeardMessages heard(AudioTermOptions{});
  // Heard from the robot's left (pi/2 in its frame) while facing +x: odom direction pi/2.
  heard.Add(1, M_PI / 2, 0.0, 70.0, 0.0, ListenMode::kOmni);
  EXPECT_NEAR(heard.Score(1, M_PI / 2, 0.0), 1.0, 1e-9);
  EXPECT_NEAR(heard.Score(1, 0.0, 0.0), 0.0, 1e-9);         // at right angles
  EXPECT_NEAR(heard.Score(1, -M_PI / 2, 0.0), -1.0, 1e-9);  // opposite
  EXPECT_NEAR(heard.Score(1, M_PI / 2, 90.0), 0.5, 1e-9);   // half its three minutes
  EXPECT_EQ(heard.Score(2, M_PI / 2, 0.0), 0.0);            // another marker
  heard.Add(1, M_PI / 2, 0.0, 55.0, 90.0, ListenMode::kOmni);  // half as loud, new
  EXPECT_NEAR(heard.Score(1, M_PI / 2, 90.0), 0.5 + 0.5, 1e-9);
  heard.Forget(180.0);
  EXPECT_EQ(heard.messages().size(), 1u);
  EXPECT_NEAR(heard.Score(1, M_PI / 2, 180.0), 0.5 * 0.5, 1e-9);
}

TEST(HeardMessages, BidirectionalKeepsOneBitAndNoneKeepsNothing) {
  HeardMessages heard(AudioTermOptions{});
  heard.Add(1, 0.3, M_PI / 2, 70.0, 0.0, ListenMode::kBidirectional);  // front -> odom pi/2
  heard.Add(1, 2.0, 0.0, 70.0, 0.0, ListenMode::kBidirectional);       // back -> odom pi
  heard.Add(1, 0.3, 0.0, 70.0, 0.0, ListenMode::kNone);
  ASSERT_EQ(heard.messages().size(), 2u);
  EXPECT_NEAR(heard.messages()[0].direction, M_PI / 2, 1e-12);
  EXPECT_NEAR(heard.messages()[1].direction, M_PI, 1e-12);
  // One bit: every direction in the heard half-plane agrees fully, every other disagrees.
  HeardMessages one(AudioTermOptions{});
  one.Add(1, 0.3, 0.0, 70.0, 0.0, ListenMode::kBidirectional);  // ahead of a robot facing +x
  EXPECT_DOUBLE_EQ(one.Score(1, 0.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(one.Score(1, 1.4, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(one.Score(1, -1.4, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(one.Score(1, 1.7, 0.0), -1.0);
  EXPECT_DOUBLE_EQ(one.Score(1, M_PI, 0.0), -1.0);
}

TEST(HeardMessages, AFullQueueDropsTheOldestAndCountsIt) {
  AudioTermOptions o;
  o.capacity = 3;
  HeardMessages heard(o);
  for (int k = 0; k < 5; ++k) heard.Add(static_cast<std::uint32_t>(k), 0.0, 0.0, 60.0, k, ListenMode::kOmni);
  EXPECT_EQ(heard.messages().size(), 3u);
  EXPECT_EQ(heard.dropped(), 2u);
  EXPECT_EQ(heard.messages().front().marker, 2u);
  o.level_full_db = o.level_floor_db;
  EXPECT_THROW(HeardMessages{o}, std::invalid_argument);
}

TEST(FrontierChoice, WithoutAudioTheNearestFrontierBeyondTheMinimumWins) {
  LocalMap map = Disc();
  // Carve a pocket of unknown at (1.6, 0): its rim is the nearest frontier beyond 1 m.
  for (int y = 0; y < 41; ++y)
    for (int x = 0; x < 41; ++x)
      if ((map.CentreOf({x, y}) - Eigen::Vector2d(1.8, 0.0)).norm() < 0.25)
        map.Set({x, y}, CellState::kUnknown, 0.0);
  HeardMessages heard(AudioTermOptions{});
  std::mt19937 rng(1);
  const auto cell = ChooseFrontier(map, FindFrontiers(map), {0.0, 0.0}, heard, 1, 0.0,
                                   Options(0.0), rng);
  ASSERT_TRUE(cell);
  EXPECT_NEAR(map.CentreOf(*cell).x(), 1.5, 0.2);
  EXPECT_NEAR(map.CentreOf(*cell).y(), 0.0, 0.3);
}

TEST(FrontierChoice, OmniMessagePullsTowardTheHeardDirection) {
  const LocalMap map = Disc();
  const std::vector<Eigen::Vector2i> frontiers = FindFrontiers(map);
  for (double heard_from : {0.0, 2.0, -2.5}) {
    HeardMessages heard(AudioTermOptions{});
    heard.Add(1, heard_from, 0.0, 60.0, 0.0, ListenMode::kOmni);
    std::mt19937 rng(3);
    for (int k = 0; k < 20; ++k) {
      const auto cell = ChooseFrontier(map, frontiers, {0.0, 0.0}, heard, 1, 1.0, Options(), rng);
      ASSERT_TRUE(cell);
      EXPECT_LT(std::abs(std::remainder(Bearing(map, *cell) - heard_from, 2 * M_PI)), 0.35)
          << heard_from;
    }
  }
}

TEST(FrontierChoice, BidirectionalMessagePullsIntoTheHeardHalfPlane) {
  const LocalMap map = Disc();
  const std::vector<Eigen::Vector2i> frontiers = FindFrontiers(map);
  // The robot faces +y; the sound came from somewhere behind it (bearing 2.6 in its frame).
  HeardMessages heard(AudioTermOptions{});
  heard.Add(1, 2.6, M_PI / 2, 60.0, 0.0, ListenMode::kBidirectional);
  std::mt19937 rng(5);
  int behind = 0;
  for (int k = 0; k < 50; ++k) {
    const auto cell =
        ChooseFrontier(map, frontiers, {0.0, 0.0}, heard, 1, 1.0, Options(0.5), rng);
    ASSERT_TRUE(cell);
    behind += map.CentreOf(*cell).y() < 0.0;
  }
  EXPECT_EQ(behind, 50);
  // Without the message the choice is spread around the ring.
  HeardMessages none(AudioTermOptions{});
  behind = 0;
  for (int k = 0; k < 200; ++k)
    behind += map.CentreOf(*ChooseFrontier(map, frontiers, {0.0, 0.0}, none, 1, 1.0,
                                           Options(0.5), rng)).y() < 0.0;
  EXPECT_GT(behind, 60);
  EXPECT_LT(behind, 140);
}

TEST(FrontierChoice, IgnoresMessagesAboutOtherMarkersAndExcludedCells) {
  const LocalMap map = Disc();
  const std::vector<Eigen::Vector2i> frontiers = FindFrontiers(map);
  HeardMessages heard(AudioTermOptions{});
  heard.Add(2, M_PI, 0.0, 70.0, 0.0, ListenMode::kOmni);
  heard.Add(1, 0.0, 0.0, 70.0, 0.0, ListenMode::kOmni);
  std::mt19937 rng(9);
  const auto cell = ChooseFrontier(map, frontiers, {0.0, 0.0}, heard, 1, 1.0, Options(), rng);
  ASSERT_TRUE(cell);
  EXPECT_GT(map.CentreOf(*cell).x(), 2.5);
  const auto other = ChooseFrontier(map, frontiers, {0.0, 0.0}, heard, 1, 1.0, Options(), rng,
                                    {*cell});
  ASSERT_TRUE(other);
  EXPECT_NE(*other, *cell);
  EXPECT_FALSE(ChooseFrontier(map, {}, {0.0, 0.0}, heard, 1, 1.0, Options(), rng));
}

}  // namespace
}  // namespace sounds_good_explorer
