// audio_propagation_query: shortest sound paths on a map, one query per input line.
//
//   audio_propagation_query --map MAP.yaml [--rule masks|convex_corners] < queries
//
// Each input line is `sx sy rx ry` (metres, map frame); each output line is
// `length_m direction_rad vertices`: the path length, the world-frame direction the sound
// arrives from at the receiver, and the number of diffraction points on the path; or
// `inf nan 0` when no path exists. No hearing threshold or range applies here.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

#include "audio_propagation/propagation_model.h"
#include "audio_propagation_args.h"
#include "grid/map_file.h"

namespace {

int Run(const audio_propagation::tools::QueryArgs& args) {
  using namespace audio_propagation;
  const std::string& map_file = args.map_file;
  PropagationOptions options;
  options.rule = args.rule;
  // Paths of any length: a level threshold would hide far paths from the check.
  options.source_level_db = 1000.0;
  options.threshold_db = -1000.0;
  try {
    const PropagationModel model(grid::LoadMapFile(map_file), options);
    std::string line;
    int line_number = 0;
    while (std::getline(std::cin, line)) {
      ++line_number;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      std::istringstream in(line);
      double sx, sy, rx, ry;
      std::string extra;
      if (!(in >> sx >> sy >> rx >> ry) || (in >> extra)) {
        std::cerr << "audio_propagation_query: stdin line " << line_number
                  << ": expected four numbers `sx sy rx ry`, got: " << line << "\n";
        return 1;
      }
      const SoundPath p = model.Path({sx, sy}, {rx, ry});
      if (p.reachable) {
        std::printf("%.6f %.6f %d\n", p.length, p.arrival_angle, p.bends);
      } else {
        std::printf("inf nan 0\n");
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "audio_propagation_query: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool(
      [&] { return Run(audio_propagation::tools::ParseQueryArgs(multirobot_audio::tools::Words(argc, argv))); });
}
