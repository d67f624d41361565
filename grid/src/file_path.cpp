#include "grid/file_path.h"

#include <filesystem>

namespace grid {

std::string CanonicalPath(const std::string& path) {
  if (path.empty()) return path;
  namespace fs = std::filesystem;
  // absolute() first: weakly_canonical leaves a relative path relative when none of it exists.
  return fs::weakly_canonical(fs::absolute(path)).string();
}

}  // namespace grid
