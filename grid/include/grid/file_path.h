#pragma once

#include <string>

namespace grid {

// The one spelling of a file's path that is stored and compared: absolute, with `.`, `..` and
// symbolic links resolved as far as the path exists (std::filesystem::weakly_canonical). The
// same file reached through a link (a catkin workspace's package is often a link in src/) and
// through its real path then compares equal. "" stays "" (no file). It never throws: a path the
// file system cannot resolve (a name too long, a folder that may not be entered) is returned
// absolute and tidied, for whoever opens it to report.
std::string CanonicalPath(const std::string& path);

}  // namespace grid
