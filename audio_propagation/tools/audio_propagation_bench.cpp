// audio_propagation_bench: how fast the propagation model builds and steps.
//
//   audio_propagation_bench --map MAP.yaml [--robots 20] [--steps 50] [--seed 1]
//                           [--rule masks|convex_corners] [--acoustics WORLD.yaml [--profile P]]
//
// Builds the model (diffraction points + visibility graph), then for each step places the robots
// at random free positions and computes the paths from every robot to every other, all robots
// transmitting. Prints one JSON object.
//
// With --acoustics (a world file whose acoustics section applies to the map), each step also
// runs what the acoustic channel does instead: the paths down to its own threshold (30 dB under
// the ambient noise), the noise at each listener from the ambient sound and the world's noise
// sources, and the decode prediction from the profile's shipped table for every pair; it
// reports that step's time and its ratio to the threshold model's step of the same run.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/propagation_model.h"
#include "grid/map_file.h"
#include "audio_propagation_args.h"
#include "world_sim/world_file.h"

namespace {

int Run(const audio_propagation::tools::BenchArgs& args) {
  using namespace audio_propagation;
  using Clock = std::chrono::steady_clock;
  const std::string& map_file = args.map_file;
  const int robots = args.robots, steps = args.steps;
  const unsigned seed = args.seed;
  const std::string& acoustics_file = args.acoustics_file;
  const std::string& profile = args.profile;

  try {
    grid::OccupancyMap map = grid::LoadMapFile(map_file);
    PropagationOptions options;
    options.rule = args.rule;
    const auto t0 = Clock::now();
    const PropagationModel model(std::move(map), options);
    const double build_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    // The acoustic channel computes paths down to its own, lower threshold (AcousticThresholdDb).
    std::unique_ptr<PropagationModel> acoustic_paths;
    std::unique_ptr<AcousticModel> acoustic;
    if (!acoustics_file.empty()) {
      const world_sim::LoadedWorld world = world_sim::LoadWorldFile(acoustics_file, map_file);
      if (!world.config.acoustics) args.usage.Fail("--acoustics: " + acoustics_file + " has no acoustics section");
      std::vector<std::string> names;
      for (int r = 0; r < robots; ++r) names.push_back(r < static_cast<int>(world.config.robots.size()) ? world.config.robots[r].name : "robot_" + std::to_string(r));
      PropagationOptions low = options;
      low.threshold_db = std::min(low.source_level_db, AcousticThresholdDb(*world.config.acoustics));
      acoustic_paths = std::make_unique<PropagationModel>(model.map(), low);
      acoustic = std::make_unique<AcousticModel>(*acoustic_paths, *world.config.acoustics,
                                                 LoadDecodeTable(ShippedDecodeTable(profile), profile), names);
    }

    std::mt19937 rng(seed);
    const grid::OccupancyMap& m = model.map();
    std::uniform_real_distribution<double> ux(0.0, m.width()), uy(0.0, m.height());
    auto random_free = [&] {
      while (true) {
        const Eigen::Vector2d p = m.CellCoordsToWorld({ux(rng), uy(rng)});
        if (m.IsFreeAt(p)) return p;
      }
    };
    std::vector<double> step_ms, acoustic_ms;
    std::size_t heard = 0;
    double delivered = 0.0;
    const std::vector<bool> all(robots, true);
    for (int k = 0; k < steps; ++k) {
      std::vector<Eigen::Vector2d> positions;
      for (int r = 0; r < robots; ++r) positions.push_back(random_free());
      const auto s0 = Clock::now();
      const auto paths = model.Compute(positions, all);
      step_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - s0).count());
      for (const auto& row : paths)
        for (const SoundPath& p : row) heard += p.audible;
      if (!acoustic) continue;
      const auto a0 = Clock::now();
      const double t = 0.37 * k;  // moves the noise sources' duty cycles along
      const auto all_paths = acoustic_paths->Compute(positions, all);
      acoustic->PreparePaths(positions, positions);
      std::vector<std::vector<Disturbance>> noise(positions.size());
      for (std::size_t r = 0; r < positions.size(); ++r) noise[r] = acoustic->NoiseAt(positions[r], t, positions);
      for (std::size_t s = 0; s < positions.size(); ++s)
        for (std::size_t r = 0; r < positions.size(); ++r)
          if (all_paths[s][r].reachable)
            delivered += acoustic->Predict(all_paths[s][r], positions[r], noise[r]).probability;
      acoustic_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - a0).count());
    }
    std::sort(step_ms.begin(), step_ms.end());
    const double median = step_ms[step_ms.size() / 2];
    double total = 0.0;
    for (double t : step_ms) total += t;
    const double pairs = static_cast<double>(robots) * (robots - 1) * steps;
    std::printf(
        "{\"map\": \"%s\", \"rule\": \"%s\", \"robots\": %d, \"steps\": %d, "
        "\"diffraction_points\": %zu, \"graph_nodes\": %zu, \"edges\": %zu, \"build_ms\": %.1f, \"step_ms\": %.3f, "
        "\"pairs_per_s\": %.0f, \"heard_fraction\": %.3f",
        map_file.c_str(), DiffractionRuleName(args.rule), robots, steps, model.diffraction_points().size(), model.graph().size(),
        model.graph().edge_count(), build_ms, median, pairs / (total / 1000.0), heard / pairs);
    if (acoustic) {
      std::sort(acoustic_ms.begin(), acoustic_ms.end());
      const double acoustic_median = acoustic_ms[acoustic_ms.size() / 2];
      std::printf(", \"acoustic_step_ms\": %.3f, \"acoustic_ratio\": %.2f, \"mean_delivery\": %.3f", acoustic_median,
                  acoustic_median / median, delivered / pairs);
    }
    std::printf("}\n");
  } catch (const std::exception& e) {
    std::cerr << "audio_propagation_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool(
      [&] { return Run(audio_propagation::tools::ParseBenchArgs(multirobot_audio::tools::Words(argc, argv))); });
}
