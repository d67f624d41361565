#pragma once

// Where the package's shipped data (decode tables, maps and worlds, launch files, rviz configs,
// helper scripts) is found at run time: the package's share folder, share/multirobot_audio/,
// looked up from the running program, never through a source-tree path compiled in. So the same
// binary works from the build tree, a catkin devel space and an install space (`cmake --install`,
// a catkin install, a binary package), wherever that was put.
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace package_data {

// The environment variable that names the share folder outright (for unusual layouts).
inline constexpr const char* kShareDirVariable = "MULTIROBOT_AUDIO_SHARE_DIR";

// Raised when no share folder can be found; says where it looked.
class PackageDataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The first of `start` and its ancestors A that holds A/share/multirobot_audio/package.xml, as
// that share folder (canonical); none: nullopt. Install spaces put programs in
// PREFIX/lib/multirobot_audio/ and data in PREFIX/share/multirobot_audio/; the build tree and the
// devel space are laid out the same way by CMake.
std::optional<std::filesystem::path> FindShareDirFrom(const std::filesystem::path& start);

// The share folder given `named` (the variable's value; null or empty: not set), which must hold
// package.xml, else the one found from `program_dir` (FindShareDirFrom). Throws PackageDataError
// naming what was looked at.
std::filesystem::path ResolveShareDir(const char* named, const std::filesystem::path& program_dir);

// ResolveShareDir for this process ($MULTIROBOT_AUDIO_SHARE_DIR, the running executable's
// folder), looked up once.
std::filesystem::path ShareDir();

// ShareDir() / relative, e.g. DataFile("tables/nava.yaml"). Whether the file exists is for the
// caller's loader to say, naming the path.
std::string DataFile(const std::string& relative);

}  // namespace package_data
