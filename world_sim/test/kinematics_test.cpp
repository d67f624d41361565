#include "world_sim/kinematics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace world_sim {
namespace {

TEST(Kinematics, StraightLine) {
  const grid::Pose2D p = IntegrateUnicycle({1.0, 2.0, M_PI / 2}, 0.3, 0.0, 2.0);
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 2.6, 1e-12);
  EXPECT_NEAR(p.yaw, M_PI / 2, 1e-12);
}

TEST(Kinematics, TurnInPlace) {
  const grid::Pose2D p = IntegrateUnicycle({1.0, 2.0, 0.0}, 0.0, 1.0, M_PI / 2);
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 2.0, 1e-12);
  EXPECT_NEAR(p.yaw, M_PI / 2, 1e-12);
}

TEST(Kinematics, ArcEndsOnTheCircle) {
  // A quarter circle of radius v / w = 1 m, starting along +x, ends at (1, 1) heading +y.
  const grid::Pose2D p = IntegrateUnicycle({0.0, 0.0, 0.0}, 0.5, 0.5, M_PI);
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 1.0, 1e-12);
  EXPECT_NEAR(p.yaw, M_PI / 2, 1e-12);
  // Many small steps land where one big step does.
  grid::Pose2D q{0.0, 0.0, 0.0};
  for (int k = 0; k < 1000; ++k) q = IntegrateUnicycle(q, 0.5, 0.5, M_PI / 1000);
  EXPECT_NEAR(q.x, 1.0, 1e-9);
  EXPECT_NEAR(q.y, 1.0, 1e-9);
}

TEST(Kinematics, HeadingWraps) {
  const grid::Pose2D p = IntegrateUnicycle({0.0, 0.0, 3.0}, 0.0, 1.0, 1.0);
  EXPECT_NEAR(p.yaw, 4.0 - 2 * M_PI, 1e-12);
}

}  // namespace
}  // namespace world_sim
