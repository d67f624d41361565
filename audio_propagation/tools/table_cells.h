#pragma once

// One cell of a decode table measured with the profile's real receiver (decode_table_bench.h
// says how): packets of random data, each alone in its own recording through a room, under a
// disturbance at an SNR; the receiver's events judged. Shared by the table's measurement and the
// model's calibration on measured rooms (model_calibration.h).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "audio_propagation/decode_table.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/moved_rooms.h"
#include "nava_modem/room_channel.h"

namespace audio_propagation::tools {

// What the receiver made of one wanted packet.
enum class Heard { kPacket, kZeroByte, kOneByte, kBadCrc, kNothing };

struct CellCounts {
  int heard[5] = {0, 0, 0, 0, 0};  // by Heard
  int false_packets = 0;           // CRC passes with data never sent
};

struct CellSetup {
  nava_modem::Profile profile = nava_modem::Profile::kNava;
  nava_modem::ModemOptions modem;
  DecodeTable table;  // packets a cell, whine and band set; cells filled by the bench
  unsigned seed = 1;
  // The speech kind's interferer (at the modem's rate): speech for the table; for a calibration
  // with a recorded noise, that recording, which then sounds as a speaker's would.
  std::vector<float> speech;
  // A measured impulse response (at the modem's rate) every packet is heard through; empty: each
  // packet's own room of the cell's RT60 and DRR, of this model.
  std::vector<float> response;
  nava_modem::RoomOptions::Model model = nava_modem::RoomOptions::Model::kStatistical;
  // Measured rooms moved to each cell's RT60 and DRR, a room drawn for every packet (the table's
  // --rooms-from); null: the rendered rooms of `model`.
  std::shared_ptr<const nava_modem::MovedRooms> moved;
};

// One 32-bit seed from a few numbers (splitmix64's finaliser over them), so that every packet of
// every cell has its own rooms, noise and data whatever thread measures it.
std::uint32_t SeedOf(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d);

// table.packets packets of cell number `cell` (its seeds) under `kind` at `snr_db`, through
// rooms of `rt60` and `drr_db` (or s.response), decoded by `profile`'s receiver.
CellCounts MeasureCell(const CellSetup& s, const nava_modem::ModemProfile& profile, std::size_t cell,
                       Interference kind, double rt60, double drr_db, double snr_db);

}  // namespace audio_propagation::tools
