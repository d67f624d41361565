#include "behaviours/wanderer.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace behaviours {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(WanderOptions, ImpossibleValuesAreNamed) {
  EXPECT_NO_THROW(ValidateOptions(WanderOptions{}));
  WanderOptions o;
  o.slow_range = o.avoid_range;
  try {
    Wanderer w(o, 1);
    FAIL() << "a slow_range not above avoid_range was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "wander slow_range (m, above avoid_range) must be > 0.45, got 0.45");
  }
  o = {};
  o.cruise_speed = -0.1;
  EXPECT_THROW(ValidateOptions(o), std::invalid_argument);
}

TEST(Wanderer, CruisesInTheOpen) {
  Wanderer w({}, 1);
  const VelocityCommand c = w.Update(std::vector<float>(8, kInf), 0.1);
  EXPECT_NEAR(c.v, WanderOptions{}.cruise_speed, 1e-12);
  EXPECT_LE(std::abs(c.w), WanderOptions{}.heading_change);
}

TEST(Wanderer, TurnsTowardsTheOpenSide) {
  Wanderer w({}, 1);
  std::vector<float> r(8, kInf);
  r[0] = 0.3f;
  r[7] = 0.4f;  // right front also close
  r[6] = 0.5f;
  const VelocityCommand c = w.Update(r, 0.1);
  EXPECT_EQ(c.v, 0.0);
  EXPECT_GT(c.w, 0.0);  // left is open
  // It keeps turning the same way while blocked, even if the sides even out.
  std::vector<float> even(8, 1.0f);
  even[0] = 0.3f;
  EXPECT_GT(w.Update(even, 0.1).w, 0.0);
}

}  // namespace
}  // namespace behaviours
