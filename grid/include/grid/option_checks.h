#pragma once

#include <string>

namespace grid {

// Bounds checks for the options structs of every component: each throws std::invalid_argument
// "<name> must be > <bound>, got <value>" (or ">=") when the value is outside (NaN always is).
void RequireAbove(const std::string& name, double value, double bound);
void RequireAtLeast(const std::string& name, double value, double bound);

}  // namespace grid
