#pragma once

#include <stdexcept>
#include <string>

namespace grid {

// Bad user input (a map or world file, a parameter). The message is one line that names the
// file, the field and what was expected, ready to print as it is.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& field, const std::string& problem)
      : std::runtime_error(file + ": " + (field.empty() ? "" : field + ": ") + problem) {}
};

}  // namespace grid
