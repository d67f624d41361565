#pragma once

#include <string>

#include "audio_propagation/direction_errors.h"

namespace audio_propagation {

// A direction table as `nava_bench --direction --errors-out FILE` writes it (degrees in the
// file, radians once loaded). Throws grid::InputError naming the file and the field: a missing
// or malformed file, a table for another profile than `expected_profile` (unless empty), a
// sample that is not [true bearing, estimate or .nan, confidence 0..1], a grid with a hole, an
// RT60 whose driest cell has no packets.
DirectionErrors LoadDirectionErrors(const std::string& path, const std::string& expected_profile);

// The shipped table of a profile (tables/PROFILE_direction.yaml in the package's share folder).
std::string ShippedDirectionErrors(const std::string& profile);

}  // namespace audio_propagation
