#pragma once

#include <string>

#include "ranging/simulated_ranging.h"

namespace audio_propagation {

// The first-arrival timing errors a profile's real receiver shows through measured rooms, as
// `nava_bench --arrival --errors-out FILE` writes them: what the simulated team's ranging draws
// every timing's error from (ranging/simulated_ranging.h). Throws grid::InputError naming the
// file and the field: a missing or malformed file, a table for another profile than
// `expected_profile` (unless empty), quantiles that are not finite, within 1 s and ascending.
ranging::ArrivalErrors LoadArrivalErrors(const std::string& path, const std::string& expected_profile);

// The shipped table of a profile (tables/PROFILE_arrival.yaml in the package's share folder).
std::string ShippedArrivalErrors(const std::string& profile);

}  // namespace audio_propagation
