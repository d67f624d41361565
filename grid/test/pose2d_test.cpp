#include "grid/pose2d.h"

#include <limits>

#include <gtest/gtest.h>

namespace grid {
namespace {

TEST(Pose2DTest, IsFiniteRefusesNanAndInfinityInAnyField) {
  EXPECT_TRUE(IsFinite({1.0, -2.0, 3.0}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(IsFinite({nan, 0.0, 0.0}));
  EXPECT_FALSE(IsFinite({0.0, -inf, 0.0}));
  EXPECT_FALSE(IsFinite({0.0, 0.0, inf}));
}

}  // namespace
}  // namespace grid
