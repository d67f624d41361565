#include "audio_propagation/path_cache.h"

#include <gtest/gtest.h>

namespace audio_propagation {
namespace {

SoundPath OfLength(double length) {
  SoundPath p;
  p.reachable = true;
  p.length = length;
  return p;
}

TEST(PathCache, FindsWhatWasInsertedPerOrderedPairOfCells) {
  PathCache cache(4);
  cache.Insert({1, 2}, {3, 4}, OfLength(5.0));
  ASSERT_TRUE(cache.Find({1, 2}, {3, 4}).has_value());
  EXPECT_DOUBLE_EQ(cache.Find({1, 2}, {3, 4})->length, 5.0);
  EXPECT_FALSE(cache.Find({3, 4}, {1, 2}).has_value());
  EXPECT_EQ(cache.hits(), 2u);
  EXPECT_EQ(cache.misses(), 1u);
}

TEST(PathCache, StaysWithinItsBoundEvictingTheLeastRecentlyUsed) {
  PathCache cache(3);
  for (int k = 0; k < 3; ++k) cache.Insert({k, 0}, {0, k}, OfLength(k));
  ASSERT_TRUE(cache.Find({0, 0}, {0, 0}).has_value());  // 0 is now the most recent
  cache.Insert({9, 9}, {9, 9}, OfLength(9.0));
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_EQ(cache.evictions(), 1u);
  EXPECT_FALSE(cache.Find({1, 0}, {0, 1}).has_value());  // 1 was the least recent
  EXPECT_TRUE(cache.Find({0, 0}, {0, 0}).has_value());
  for (int k = 0; k < 100; ++k) cache.Insert({k, k}, {k, 1}, OfLength(k));
  EXPECT_EQ(cache.size(), 3u);
}

TEST(PathCache, ZeroCapacityKeepsNothing) {
  PathCache cache(0);
  cache.Insert({1, 1}, {2, 2}, OfLength(1.0));
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_FALSE(cache.Find({1, 1}, {2, 2}).has_value());
}

TEST(PathCache, CellsOffTheKeyRangeAreNeverCached) {
  PathCache cache(4);
  // A robot with no pose yet is put far off the map; it must not alias a real cell.
  cache.Insert({-20000000, -20000000}, {2, 2}, OfLength(1.0));
  cache.Insert({2, 2}, {70000, 1}, OfLength(1.0));
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_FALSE(cache.Find({-20000000, -20000000}, {2, 2}).has_value());
  EXPECT_EQ(cache.misses(), 1u);
}

TEST(PathCache, ReinsertReplaces) {
  PathCache cache(2);
  cache.Insert({1, 1}, {2, 2}, OfLength(1.0));
  cache.Insert({1, 1}, {2, 2}, OfLength(2.0));
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_DOUBLE_EQ(cache.Find({1, 1}, {2, 2})->length, 2.0);
}

}  // namespace
}  // namespace audio_propagation
