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

// Whether `path` names a regular file (a link to one counts). Never throws: where the file system
// cannot tell (a name too long, a folder that may not be entered), false, and `why` (when given)
// says what it said; for a file that is not there, "no such file"; for a folder or a device, "not
// a regular file". A loader turns false into its own InputError naming the field.
bool IsRegularFile(const std::string& path, std::string* why = nullptr);

}  // namespace grid
