// world_sim_bench: how fast the simulator steps a team with every sensor on.
//
//   world_sim_bench [--map MAP.yaml] [--robots N] [--seconds S] [--seed K]
//
// Places N wandering robots at random free poses on the map (34 x 14 m office by default),
// steps the world for S simulated seconds with IR scans at 10 Hz, fiducial images at 5 Hz and
// odometry and battery every step, and prints figures; the last line is
// `real_time_factor R`, simulated seconds per wall-clock second.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>

#include "grid/input_error.h"
#include "grid/map_file.h"
#include "behaviours/wanderer.h"
#include "world_sim/world.h"
#include "tool_args/usage_error.h"
#include "world_sim/world_file.h"
#include "world_sim_bench_args.h"

namespace {

// Random robots that fit the free space without touching each other, and a few markers.
world_sim::WorldConfig RandomTeam(const grid::OccupancyMap& map, const world_sim::tools::WorldSimBenchArgs& args) {
  world_sim::WorldConfig c;
  c.map_file = args.map;
  c.seed = args.seed;
  std::mt19937 rng(args.seed);
  std::uniform_real_distribution<double> x(0.0, map.width_m()), y(0.0, map.height_m()),
      yaw(-M_PI, M_PI);
  int attempts = 0;
  while (static_cast<int>(c.robots.size()) < args.robots) {
    if (++attempts > 1000000) world_sim::tools::RefuseWorldSimBench("cannot place " + std::to_string(args.robots) + " robots on " + args.map);
    const Eigen::Vector2d p = map.CellCoordsToWorld(Eigen::Vector2d(x(rng), y(rng)) / map.resolution());
    world_sim::WorldConfig trial = c;
    trial.robots.push_back({"robot_" + std::to_string(c.robots.size()), {p.x(), p.y(), yaw(rng)},
                            world_sim::Microphone::kOmni, 1.0});
    try {
      world_sim::ValidateWorld(args.map, trial, map);
    } catch (const grid::InputError&) {
      continue;
    }
    c = trial;
  }
  while (c.markers.size() < 10) {
    const Eigen::Vector2d p = map.CellCoordsToWorld(Eigen::Vector2d(x(rng), y(rng)) / map.resolution());
    if (map.IsFreeAt(p)) c.markers.push_back({static_cast<std::uint32_t>(c.markers.size()), p.x(), p.y()});
  }
  return c;
}

int Run(const world_sim::tools::WorldSimBenchArgs& args) {
  try {
    const grid::OccupancyMap map = grid::LoadMapFile(args.map);
    world_sim::World world(map, RandomTeam(map, args));
    std::vector<behaviours::Wanderer> brains;
    for (int k = 0; k < args.robots; ++k) brains.emplace_back(behaviours::WanderOptions{}, args.seed + k);

    const auto steps = static_cast<std::uint64_t>(std::llround(args.seconds / world.options().step));
    const auto start = std::chrono::steady_clock::now();
    for (std::uint64_t s = 0; s < steps; ++s) {
      // Controllers react to each new scan, as the ROS controllers do.
      for (int k = 0; k < args.robots; ++k) {
        if (world.robots()[k].scan_step != world.steps()) continue;
        const auto cmd = brains[k].Update(world.robots()[k].scan, world.options().scan_period);
        world.SetCommand(k, cmd.v, cmd.w);
      }
      world.Step();
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::printf("map %s (%.1f x %.1f m, %d x %d cells)\n", args.map.c_str(), map.width_m(),
                map.height_m(), map.width(), map.height());
    std::printf("robots %d\nsimulated_s %.1f\nsteps %llu\nwall_s %.3f\n", args.robots,
                world.elapsed(), static_cast<unsigned long long>(steps), wall);
    std::printf("distance_m %.1f\ncollisions %d\n", world.TotalDistance(), world.TotalCollisions());
    std::printf("real_time_factor %.0f\n", world.elapsed() / wall);
  } catch (const std::exception& e) {
    std::cerr << "world_sim_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool(
      [&] { return Run(world_sim::tools::ParseWorldSimBenchArgs(multirobot_audio::tools::Words(argc, argv))); });
}
