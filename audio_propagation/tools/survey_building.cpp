#include "survey_building.h"

#include <cmath>
#include <filesystem>
#include <set>

#include "grid/input_error.h"
#include "grid/yaml_fields.h"

namespace audio_propagation::tools {

BuildingSurvey ReadBuildingSurvey(const std::string& path) {
  namespace fs = std::filesystem;
  const grid::YamlFields root = grid::YamlFields::Load(path, "building survey");
  root.ExpectOnlyKeys({"source_level_db", "rooms"});
  BuildingSurvey survey;
  survey.source_level_db = root.Number("source_level_db", survey.source_level_db);
  if (!std::isfinite(survey.source_level_db) || std::abs(survey.source_level_db) > 1000.0) {
    root.Fail("source_level_db", "expected a level in [-1000, 1000] dB, got " + std::to_string(survey.source_level_db));
  }
  const fs::path folder = fs::path(path).parent_path();
  std::set<std::string> names;
  for (const grid::YamlFields& r : root.Elements("rooms")) {
    r.ExpectOnlyKeys({"name", "box", "distance", "recordings"});
    SurveyedRoom room;
    room.name = r.String("name");
    if (room.name.empty() || room.name.find_first_of(":{}[],#'\"\n") != std::string::npos) {
      r.Fail("name", "expected a plain name (no YAML punctuation), got '" + room.name + "'");
    }
    if (!names.insert(room.name).second) r.Fail("name", "a second room named '" + room.name + "'");
    const std::vector<double> box = r.Numbers("box", 4, "[min_x, min_y, max_x, max_y]");
    if (!(box[0] < box[2] && box[1] < box[3])) {
      r.Fail("box", "expected min_x < max_x and min_y < max_y, got [" + std::to_string(box[0]) + ", " +
                        std::to_string(box[1]) + ", " + std::to_string(box[2]) + ", " + std::to_string(box[3]) + "]");
    }
    room.box = {box[0], box[1], box[2], box[3]};
    room.distance = r.Number("distance");
    if (!(room.distance > 0.0 && room.distance <= 1000.0)) {
      r.Fail("distance", "expected the robots' distance in (0, 1000] m, got " + std::to_string(room.distance));
    }
    const YAML::Node list = r.node()["recordings"];
    if (!list || !list.IsSequence() || list.size() == 0) {
      r.Fail("recordings", "expected a list of the room's recordings");
    }
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (!list[k].IsScalar()) r.Fail("recordings", "expected file names, element " + std::to_string(k) + " is not one");
      const fs::path file = fs::path(list[k].as<std::string>()).is_absolute()
                                ? fs::path(list[k].as<std::string>())
                                : folder / list[k].as<std::string>();
      std::error_code error;
      if (!fs::is_regular_file(file, error)) r.Fail("recordings", "no such file: " + file.string());
      room.recordings.push_back(file.lexically_normal().string());
    }
    survey.rooms.push_back(room);
  }
  if (survey.rooms.empty()) root.Fail("rooms", "expected at least one room");
  return survey;
}

}  // namespace audio_propagation::tools
