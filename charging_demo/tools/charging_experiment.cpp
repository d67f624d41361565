// charging_experiment: the charging trial of thesis section 7.2 in process, no ROS. Robots
// wander on duty, look for a charger when their battery runs low, wait for the audio local
// mutex at a safe distance and dock only while they hold it.
//
//   charging_experiment [--map MAP.yaml | --world WORLD.yaml] [--robots 4] [--chargers 1]
//     [--hours 2] [--seeds 10] [--seed 1] [--out DIR] [--timeline FILE.png]
//
// Each seed draws a world (chargers and robots at random on the map; --world keeps one world
// and varies the noise) and runs it for the given hours. Writes into DIR (default
// charging_results): trials.csv (a row per seed), robots.csv (a row per robot and seed),
// worlds/seed_NNN.yaml (each world, to replay in ROS); --timeline draws the first seed's trial.
// Ends with the line
//   double_dockings D robots_flat F charges C utilisation U mean_wait_s W
// summed (D, F, C) or averaged (U over trials, W over charges) over every seed.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "charging_demo/charging_timeline.h"
#include "charging_demo/charging_trial.h"
#include "charging_demo/charging_world.h"
#include "grid/input_error.h"
#include "grid/map_file.h"
#include "tool_args/parallel_for.h"
#include "tool_args/progress_bar.h"
#include "tool_args/tool_args.h"
#include "world_sim/world_file.h"

namespace {

using namespace charging_demo;
namespace fs = std::filesystem;

const char* kUsage =
    "charging_experiment [--map MAP.yaml | --world WORLD.yaml] [--robots 4] [--chargers 1]\n"
    "  [--hours 2] [--seeds 10] [--seed 1] [--out charging_results] [--timeline FILE.png]\n"
    "  [--hearing 15] [--spacing 12] [--low 0.3] [--full 0.98] [--wait-distance 1]\n"
    "  [--lock-timeout 1500] [--threads 0]";

double Mean(const std::vector<double>& values) {
  if (values.empty()) return std::nan("");
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

struct Seeded {
  std::uint32_t seed = 0;
  world_sim::WorldConfig world;
  ChargingTrialResult result;
};

void WriteCsv(const fs::path& out, const std::vector<Seeded>& runs) {
  std::ofstream trials(out / "trials.csv"), robots(out / "robots.csv");
  trials << "seed,robots,chargers,hours,charges,double_dockings,robots_flat,utilisation,mean_wait_s,"
            "give_ups,redocks,retraces,collisions,lock_packets,queue_overflows\n";
  robots << "seed,robot,charges,give_ups,redocks,retraces,wall_loops,min_battery,flat,mean_wait_s,max_wait_s,"
            "mean_seek_s\n";
  for (const Seeded& run : runs) {
    const ChargingTrialResult& r = run.result;
    std::uint64_t give_ups = 0, redocks = 0, retraces = 0;
    for (std::size_t k = 0; k < r.robots.size(); ++k) {
      const RobotRecord& robot = r.robots[k];
      give_ups += robot.give_ups;
      redocks += robot.redocks;
      retraces += robot.retraces;
      const double max_wait = robot.waits.empty() ? std::nan("")
                                                  : *std::max_element(robot.waits.begin(), robot.waits.end());
      robots << run.seed << ',' << k << ',' << robot.charges << ',' << robot.give_ups << ','
             << robot.redocks << ',' << robot.retraces << ',' << robot.wall_loops << ',' << robot.min_battery << ',' << (robot.flat ? 1 : 0) << ','
             << Mean(robot.waits) << ',' << max_wait << ',' << Mean(robot.seeks) << '\n';
    }
    trials << run.seed << ',' << r.robots.size() << ',' << r.charger_busy.size() << ','
           << r.duration / 3600.0 << ',' << r.charges() << ',' << r.double_dockings << ','
           << r.flat_robots() << ',' << r.utilisation() << ',' << r.mean_wait() << ',' << give_ups
           << ',' << redocks << ',' << retraces << ',' << r.collisions << ',' << r.packets_sent << ','
           << r.queue_overflows << '\n';
  }
  if (!trials || !robots) throw std::runtime_error((out / "trials.csv").string() + ": cannot write");
}

int Run(const multirobot_audio::tools::ToolArgs& args) {
  const std::string world_file = args.String("--world", "");
  const std::string map_file = args.String("--map", MULTIROBOT_AUDIO_MAPS_DIR "/office.yaml");
  ChargingWorldOptions placement;
  placement.robots = static_cast<int>(args.Int("--robots", placement.robots, 1, 255));
  placement.chargers = static_cast<int>(args.Int("--chargers", placement.chargers, 1, 1000));
  placement.charger_spacing = args.Double("--spacing", placement.charger_spacing, 0.0, 1e6);
  const double hours = args.Double("--hours", 2.0, 1e-3, 1000.0);
  const int seeds = static_cast<int>(args.Int("--seeds", 10, 1, 100000));
  const std::uint32_t first_seed = static_cast<std::uint32_t>(args.Int("--seed", 1, 0, 4294967295L));
  const double hearing = args.Double("--hearing", 15.0, 0.0, 1e6);
  ChargingTrialOptions options;
  options.duration = hours * 3600.0;
  ChargingOptions& charging = options.controller.charging;
  charging.low_battery = args.Double("--low", charging.low_battery, -1e9, 1e9);
  charging.full_battery = args.Double("--full", charging.full_battery, -1e9, 1e9);
  charging.wait_distance = args.Double("--wait-distance", charging.wait_distance, -1e9, 1e9);
  charging.lock_timeout = args.Double("--lock-timeout", charging.lock_timeout, -1e9, 1e9);
  const int threads = static_cast<int>(args.Int("--threads", 0, 0, 256));
  const std::string out_dir = args.String("--out", "charging_results");
  const std::string timeline = args.String("--timeline", "");
  if (!world_file.empty() && (!args.String("--robots", "").empty() || !args.String("--chargers", "").empty() ||
                              !args.String("--map", "").empty() || !args.String("--spacing", "").empty()))
    args.Fail("--world gives the robots, chargers and map: drop --robots, --chargers, --map and --spacing");
  args.CheckAllUsed();
  // The options' own checks name the field (a threshold outside (0, 1), ...) before any work.
  charging.chargers = {placement.first_marker};
  ValidateOptions(options.controller);
  ValidateOptions(options);

  std::vector<Seeded> runs(seeds);
  grid::OccupancyMap map;
  if (!world_file.empty()) {
    world_sim::LoadedWorld loaded = world_sim::LoadWorldFile(world_file);
    ValidateChargingWorld(world_file, loaded.config);
    map = std::move(loaded.map);
    for (int s = 0; s < seeds; ++s) runs[s].world = loaded.config;
  } else {
    const std::string absolute = fs::absolute(map_file).lexically_normal().string();
    map = grid::LoadMapFile(absolute);
    for (int s = 0; s < seeds; ++s) {
      std::mt19937 rng(first_seed + static_cast<std::uint32_t>(s));
      runs[s].world = RandomChargingWorld(map, absolute, world_sim::RobotModel{}, placement, rng);
    }
  }
  const fs::path out(out_dir);
  fs::create_directories(out / "worlds");
  for (int s = 0; s < seeds; ++s) {
    runs[s].seed = first_seed + static_cast<std::uint32_t>(s);
    runs[s].world.seed = runs[s].seed;
    char name[32];
    std::snprintf(name, sizeof name, "seed_%03u.yaml", runs[s].seed);
    world_sim::SaveWorldFile((out / "worlds" / name).string(), runs[s].world);
  }

  audio_propagation::PropagationOptions audio;
  audio.max_range = hearing;
  const audio_propagation::PropagationModel model(map, audio);
  std::fprintf(stderr, "charging_experiment: %d seeds x %.2f h, %zu robots, %zu chargers\n", seeds, hours,
               runs[0].world.robots.size(), runs[0].world.chargers.size());
  multirobot_audio::tools::ProgressBar bar("trials");
  const auto start = std::chrono::steady_clock::now();
  multirobot_audio::tools::ParallelFor(
      runs.size(), threads,
      [&](std::size_t i) {
        ChargingTrialOptions o = options;
        o.seed = runs[i].seed;
        runs[i].result = RunChargingTrial(map, runs[i].world, model, o);
      },
      bar);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  WriteCsv(out, runs);
  if (!timeline.empty())
    WriteChargingTimeline(timeline, runs[0].result, charging.low_battery,
                          "charging trial, seed " + std::to_string(runs[0].seed) + ": " +
                              std::to_string(runs[0].world.robots.size()) + " robots, " +
                              std::to_string(runs[0].world.chargers.size()) + " chargers");

  std::uint64_t double_dockings = 0, charges = 0;
  std::size_t flat = 0;
  double utilisation = 0.0, wait_sum = 0.0;
  std::size_t waits = 0;
  for (const Seeded& run : runs) {
    double_dockings += run.result.double_dockings;
    charges += run.result.charges();
    flat += run.result.flat_robots();
    utilisation += run.result.utilisation() / runs.size();
    for (const RobotRecord& r : run.result.robots)
      for (double w : r.waits) wait_sum += w, ++waits;
  }
  std::printf("trials %d wall_s %.1f out %s\n", seeds, wall, out_dir.c_str());
  std::printf("double_dockings %llu robots_flat %zu charges %llu utilisation %.3f mean_wait_s %.1f\n",
              static_cast<unsigned long long>(double_dockings), flat,
              static_cast<unsigned long long>(charges), utilisation, waits ? wait_sum / waits : std::nan(""));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const multirobot_audio::tools::ToolArgs args("charging_experiment", kUsage, argc, argv);
  try {
    return Run(args);
  } catch (const std::exception& e) {
    std::cerr << "charging_experiment: " << e.what() << "\n";
  }
  return 1;
}
