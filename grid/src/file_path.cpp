#include "grid/file_path.h"

#include <filesystem>
#include <system_error>

namespace grid {

std::string CanonicalPath(const std::string& path) {
  if (path.empty()) return path;
  namespace fs = std::filesystem;
  std::error_code error;
  // absolute() first: weakly_canonical leaves a relative path relative when none of it exists.
  fs::path absolute = fs::absolute(path, error);
  if (error) absolute = fs::path(path);
  const fs::path canonical = fs::weakly_canonical(absolute, error);
  // A name the file system cannot resolve (too long, a folder we may not enter) is kept as
  // written, tidied: whoever opens it reports the file and why it cannot be read.
  if (error) return absolute.lexically_normal().string();
  return canonical.string();
}

bool IsRegularFile(const std::string& path, std::string* why) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  std::string problem;
  if (status.type() == fs::file_type::not_found) {
    problem = "no such file";
  } else if (error) {
    problem = error.message();
  } else if (status.type() != fs::file_type::regular) {
    problem = "not a regular file";
  }
  if (why) *why = problem;
  return problem.empty();
}

}  // namespace grid
