#pragma once

// What the fuzz targets that load files share: a scratch folder and a small map.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fuzz {

// A folder of this process's own under TMPDIR (or /tmp), removed when the fuzzer exits.
class ScratchDir {
 public:
  static const std::string& Path() {
    static const ScratchDir dir;
    return dir.path_;
  }

 private:
  ScratchDir() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/multirobot_fuzz.XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a scratch folder " + pattern);
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::string path_;
};

// Writes `size` bytes to `name` in the scratch folder; returns the file's path.
inline std::string WriteScratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = ScratchDir::Path() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("cannot write " + path);
  return path;
}

inline std::string WriteScratch(const std::string& name, const std::string& text) {
  return WriteScratch(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

// A small map for the loaders that need one: tiny.yaml and tiny.pgm in the scratch folder, a
// 2 x 2 m room (20 x 20 cells of 0.1 m) walled round. Returns the YAML's path.
inline std::string TinyMap() {
  static const std::string yaml = [] {
    std::string pgm = "P5\n20 20\n255\n";
    for (int r = 0; r < 20; ++r) {
      for (int c = 0; c < 20; ++c) pgm += (r == 0 || c == 0 || r == 19 || c == 19) ? '\0' : '\xfe';
    }
    WriteScratch("tiny.pgm", pgm);
    return WriteScratch("tiny.yaml", "image: tiny.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\n");
  }();
  return yaml;
}

}  // namespace fuzz
