#include "world_sim/wanderer.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "grid/map_file.h"
#include "world_sim/world.h"
#include "world_sim/world_file.h"

namespace world_sim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

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

TEST(Wanderer, TeamWandersTheOfficeWithFewCollisions) {
  const LoadedWorld loaded = LoadWorldFile(std::string(PROJECT_MAPS_DIR) + "/office_world.yaml");
  World world(loaded.map, loaded.config);
  std::vector<Wanderer> brains;
  for (std::size_t k = 0; k < world.robots().size(); ++k) brains.emplace_back(WanderOptions{}, k);
  for (int step = 0; step < 60 * 50; ++step) {  // a simulated minute
    for (std::size_t k = 0; k < world.robots().size(); ++k) {
      const VelocityCommand c = brains[k].Update(world.robots()[k].scan, world.options().step);
      world.SetCommand(k, c.v, c.w);
    }
    world.Step();
  }
  for (const RobotState& r : world.robots()) EXPECT_GT(r.distance, 3.0) << r.name << " barely moved";
  EXPECT_LE(world.TotalCollisions(), 5);
}

}  // namespace
}  // namespace world_sim
