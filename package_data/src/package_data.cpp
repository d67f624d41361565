#include "package_data/package_data.h"

#include <cstdlib>
#include <system_error>

namespace package_data {
namespace fs = std::filesystem;

namespace {

bool HoldsPackage(const fs::path& share) {
  std::error_code error;
  return fs::is_regular_file(share / "package.xml", error);
}

fs::path RunningExecutable() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) throw PackageDataError(std::string("cannot read /proc/self/exe to find the package's data: ") + error.message());
  return self;
}

}  // namespace

std::optional<fs::path> FindShareDirFrom(const fs::path& start) {
  std::error_code error;
  fs::path at = fs::weakly_canonical(start, error);
  if (error) at = start;
  while (true) {
    const fs::path share = at / "share" / "multirobot_audio";
    if (HoldsPackage(share)) return fs::weakly_canonical(share);
    if (!at.has_parent_path() || at.parent_path() == at) return std::nullopt;
    at = at.parent_path();
  }
}

fs::path ResolveShareDir(const char* named, const fs::path& program_dir) {
  if (named != nullptr && *named != '\0') {
    const fs::path share(named);
    if (!HoldsPackage(share)) {
      throw PackageDataError(std::string(kShareDirVariable) + "=" + named +
                             ": expected the package's share folder, holding package.xml");
    }
    return fs::weakly_canonical(share);
  }
  if (auto found = FindShareDirFrom(program_dir)) return *found;
  throw PackageDataError("cannot find the multirobot_audio share folder (share/multirobot_audio/package.xml) in " +
                         program_dir.string() + " or any folder above it; set " + kShareDirVariable);
}

fs::path ShareDir() {
  // Looked up once: the executable and the environment do not change while it runs.
  static const fs::path share = ResolveShareDir(std::getenv(kShareDirVariable), RunningExecutable().parent_path());
  return share;
}

std::string DataFile(const std::string& relative) { return (ShareDir() / relative).string(); }

}  // namespace package_data
