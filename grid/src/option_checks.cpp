#include "grid/option_checks.h"

#include <sstream>
#include <stdexcept>

namespace grid {

namespace {

[[noreturn]] void Fail(const std::string& name, const char* relation, double bound, double value) {
  std::ostringstream message;
  message << name << " must be " << relation << ' ' << bound << ", got " << value;
  throw std::invalid_argument(message.str());
}

}  // namespace

void RequireAbove(const std::string& name, double value, double bound) {
  if (!(value > bound)) Fail(name, ">", bound, value);
}

void RequireAtLeast(const std::string& name, double value, double bound) {
  if (!(value >= bound)) Fail(name, ">=", bound, value);
}

}  // namespace grid
