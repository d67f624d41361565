#pragma once

// What a robot says of each teammate it has heard (the audio/teammates topic): the range from
// two-way ranging and the bearing of its latest packet, each where known. One merge for the
// real link and the simulation, so that both say the same the same way.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ranging/two_way_ranger.h"

namespace ranging {

// A teammate's latest packet as heard here: where it came from (rad in the robot's frame).
struct HeardBearing {
  double bearing = 0.0;
  double confidence = 0.0;  // 0 to 1
  double at = 0.0;          // s, when heard (the clock `now` is told on below)
};

struct TeammateView {
  std::string name;
  std::optional<Range> range;
  std::optional<HeardBearing> bearing;
  double bearing_age = 0.0;  // s (0 without a bearing)
};

// Every teammate with a range or a bearing, by name; ages against `now`.
std::vector<TeammateView> ViewTeammates(const std::vector<Range>& ranges,
                                        const std::map<std::string, HeardBearing>& bearings, double now);

}  // namespace ranging
