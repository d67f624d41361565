// The map loader (map_server's YAML and its PGM or PNG image), which reads the maps users draw.
// Byte 0 chooses what the rest is:
//   even: the map's YAML, beside the small image tiny.pgm (fuzz_support.h) in the same folder;
//   odd:  the image's bytes, named by a fixed YAML (byte 0's bit 1: negated).
// A map it cannot load must be refused with grid::InputError; one it loads must be as big as
// its image says.
#include <cstdint>
#include <cstdlib>

#include "fuzz_support.h"
#include "grid/input_error.h"
#include "grid/map_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  fuzz::TinyMap();
  std::string yaml;
  if (data[0] & 1) {
    fuzz::WriteScratch("fuzzed_image", data + 1, size - 1);
    yaml = fuzz::WriteScratch("image_map.yaml", std::string("image: fuzzed_image\nresolution: 0.05\n"
                                                            "origin: [-1.0, 2.0, 0.5]\nnegate: ") +
                                                    ((data[0] & 2) ? "1\n" : "0\n"));
  } else {
    yaml = fuzz::WriteScratch("map.yaml", data + 1, size - 1);
  }
  try {
    const grid::OccupancyMap map = grid::LoadMapFile(yaml);
    if (map.width() < 1 || map.height() < 1 || !(map.resolution() > 0.0)) std::abort();
  } catch (const grid::InputError&) {
  }
  return 0;
}
