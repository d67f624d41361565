// The acoustic decode table loader (audio_propagation/decode_table.h), on a table file. A table
// it cannot load must be refused with grid::InputError; one it loads must give fractions that
// sum to at most 1 wherever it is looked up (NaN and infinite figures included), and save
// (SaveDecodeTable) to a file that loads again.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "audio_propagation/decode_table.h"
#include "fuzz_support.h"
#include "grid/input_error.h"

using namespace audio_propagation;

namespace {

void CheckLookups(const DecodeTable& table) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < kInterferenceCount; ++k) {
    for (double snr : {-inf, table.snr_db.front() - 1.0, (table.snr_db.front() + table.snr_db.back()) / 2.0, inf, nan}) {
      for (double drr : {table.drr_db.front(), (table.drr_db.front() + table.drr_db.back()) / 2.0, nan}) {
        for (double rt60 : {table.rt60.back() + 1.0, nan}) {
          const DecodeOutcome o = table.Lookup(static_cast<Interference>(k), snr, drr, rt60);
          for (double f : {o.packet, o.zero_byte, o.one_byte, o.bad_crc}) {
            if (!(f >= -1e-9 && f <= 1.0 + 1e-9)) std::abort();
          }
          if (o.Nothing() < -1e-6) std::abort();
        }
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::WriteScratch("table.yaml", data, size);
  DecodeTable table;
  try {
    table = LoadDecodeTable(path);
  } catch (const grid::InputError&) {
    return 0;
  }
  CheckLookups(table);
  const std::string saved = fuzz::ScratchDir::Path() + "/saved_table.yaml";
  SaveDecodeTable(saved, table);
  const DecodeTable again = LoadDecodeTable(saved);
  if (again.cells.size() != table.cells.size() || again.snr_db != table.snr_db) std::abort();
  return 0;
}
