#include "ranging/teammate_view.h"

#include <algorithm>

namespace ranging {

std::vector<TeammateView> ViewTeammates(const std::vector<Range>& ranges,
                                        const std::map<std::string, HeardBearing>& bearings, double now) {
  std::map<std::string, TeammateView> by_name;
  for (const Range& r : ranges) {
    TeammateView& v = by_name[r.teammate];
    v.name = r.teammate;
    v.range = r;
  }
  for (const auto& [name, b] : bearings) {
    TeammateView& v = by_name[name];
    v.name = name;
    v.bearing = b;
    v.bearing_age = std::max(0.0, now - b.at);
  }
  std::vector<TeammateView> out;
  for (auto& [name, v] : by_name) out.push_back(std::move(v));
  return out;
}

}  // namespace ranging
