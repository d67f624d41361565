// A team of wanderers (behaviours/) driving in the simulated office.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "behaviours/wanderer.h"
#include "grid/map_file.h"
#include "world_sim/world.h"
#include "world_sim/world_file.h"

namespace world_sim {
namespace {

TEST(WanderingTeam, WandersTheOfficeWithFewCollisions) {
  const LoadedWorld loaded = LoadWorldFile(std::string(PROJECT_MAPS_DIR) + "/office_world.yaml");
  World world(loaded.map, loaded.config);
  std::vector<behaviours::Wanderer> brains;
  for (std::size_t k = 0; k < world.robots().size(); ++k) brains.emplace_back(behaviours::WanderOptions{}, k);
  for (int step = 0; step < 60 * 50; ++step) {  // a simulated minute
    for (std::size_t k = 0; k < world.robots().size(); ++k) {
      const behaviours::VelocityCommand c = brains[k].Update(world.robots()[k].scan, world.options().step);
      world.SetCommand(k, c.v, c.w);
    }
    world.Step();
  }
  for (const RobotState& r : world.robots()) EXPECT_GT(r.distance, 3.0) << r.name << " barely moved";
  EXPECT_LE(world.TotalCollisions(), 5);
}

}  // namespace
}  // namespace world_sim
