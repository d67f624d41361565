#pragma once

// A building's survey, room by room (nava_survey --building FILE.yaml): which recordings were
// made in which room, how far apart the robots stood, and where each room lies on the map, so
// that the survey can write a world's acoustics with a region per room.
//
//   source_level_db: 70          # the robots' packet level at 1 m (optional)
//   rooms:
//     - {name: kitchen, box: [0, 0, 5, 4], distance: 3.0, recordings: [kitchen_a.wav, kitchen_b.wav]}
//
// Recordings are relative to the file's folder.
#include <array>
#include <string>
#include <vector>

namespace audio_propagation::tools {

struct SurveyedRoom {
  std::string name;
  std::array<double, 4> box{};  // min_x, min_y, max_x, max_y (m)
  double distance = 0.0;        // m between the robots while recording
  std::vector<std::string> recordings;
};

struct BuildingSurvey {
  double source_level_db = 70.0;
  std::vector<SurveyedRoom> rooms;
};

// Throws grid::InputError naming the file and the field for a malformed file, a room without a
// name, box, distance or recording, a box whose min is not under its max, a distance outside
// (0, 1000] m, two rooms of one name, or a recording that is not there.
BuildingSurvey ReadBuildingSurvey(const std::string& path);

}  // namespace audio_propagation::tools
