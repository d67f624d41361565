// The world file loader (robots, markers, chargers, the robot model and the acoustics section),
// on a world file beside the small map tiny.yaml (fuzz_support.h). A world it cannot load must be
// refused with grid::InputError; one it loads must save (SaveWorldFile) to a file that loads
// again to the same robots.
#include <cstdint>
#include <cstdlib>

#include "fuzz_support.h"
#include "grid/input_error.h"
#include "world_sim/world_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::TinyMap();
  const std::string path = fuzz::WriteScratch("world.yaml", data, size);
  world_sim::LoadedWorld world;
  try {
    world = world_sim::LoadWorldFile(path);
  } catch (const grid::InputError&) {
    return 0;
  }
  const std::string saved = fuzz::ScratchDir::Path() + "/saved_world.yaml";
  world_sim::SaveWorldFile(saved, world.config);
  const world_sim::LoadedWorld again = world_sim::LoadWorldFile(saved);
  if (again.config.robots.size() != world.config.robots.size()) std::abort();
  for (std::size_t k = 0; k < world.config.robots.size(); ++k) {
    if (again.config.robots[k].name != world.config.robots[k].name) std::abort();
  }
  if (again.config.acoustics.has_value() != world.config.acoustics.has_value()) std::abort();
  return 0;
}
