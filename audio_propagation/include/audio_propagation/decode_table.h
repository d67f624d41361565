#pragma once

// A decode table: what a modem profile's real receiver makes of packets heard through a room,
// measured by running it on rendered room audio (decode_table_bench --profile PROFILE), against the
// signal-to-noise ratio, the direct-to-reverberant ratio, the reverberation time and the kind of
// disturbance. The `acoustic` channel model (acoustic_model.h) looks a link's figures up in it to
// decide whether a simulated packet is decoded, and if not, what noise the receiver reports.
//
// Definitions (those of nava_modem/room_channel.h, so table and renderer agree):
//   signal power  the mean square of the reverberant packet over the samples where it sounds
//                 (direct plus reverberant sound);
//   noise power   the mean square of the disturbance over the recording, all frequencies;
//   SNR           10 log10(signal / noise), whatever the disturbance's kind;
//   DRR           the room impulse response's direct-to-reverberant energy ratio.
// For the `packet` kind the disturbance is another packet of the same profile, through the same
// room, starting anywhere within one packet length of the wanted one.
//
// File format (YAML):
//   profile: room                 # nava | room
//   packets: 12                   # per cell
//   whine_hz: 2500                # the whine of the whine cells
//   band_hz: [600, 5400]          # the profile's band
//   command: "decode_table_bench --profile room ..."
//   rooms: measured-like          # optional (default statistical): the rooms the packets were
//                                 # heard through (nava_modem::RoomOptions::Model)
//   lead_s: 1                     # optional (default 0.3, as tables were measured before the
//                                 # field): s of the disturbance before each packet
//   snr_db: [-15, -12, ...]       # ascending
//   drr_db: [-30, ..., 24]        # ascending
//   rt60: [0.3, 0.6, 1.2]         # ascending, s
//   kinds:                        # every kind, each a list over rt60 of lists over drr of
//     white: [[[p, z, o, b], ...]]   # lists over snr of [packet, zero_byte, one_byte, bad_crc]
//     ...
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "nava_modem/room_channel.h"
#include "world_sim/acoustics.h"

namespace audio_propagation {

// The sample rate the tables are measured at (decode_table_bench renders at the modems' default
// rate, nava_modem::ModemOptions::sample_rate).
constexpr double kTableSampleRate = 48000.0;

// How long the disturbance sounds before a packet in what decode_table_bench measures (and what
// audio_channel_validate renders to hold the model against): the steady state of a robot whose
// fan or hiss has run for long. The room receiver needs about half a second to get there
// (docs/audio_link.md, "the noise before a packet"). Tables measured before this was 1 s gave
// 0.3 s, which a table file says by having no `lead_s`.
constexpr double kTableLeadSeconds = 1.0;
constexpr double kFormerTableLeadSeconds = 0.3;

// The disturbance a packet is judged against.
enum class Interference { kWhite, kPink, kSpeech, kWhine, kPacket };
constexpr std::size_t kInterferenceCount = 5;
std::optional<Interference> ParseInterference(const std::string& name);  // white ... packet
const char* InterferenceName(Interference kind);
Interference FromNoiseKind(world_sim::NoiseKind kind);

// What the receiver reported for the packets of one cell, as fractions of the packets sent. The
// rest (1 minus the sum) it did not report at all.
struct DecodeOutcome {
  double packet = 0.0;     // decoded, with the right data
  double zero_byte = 0.0;  // noise: a carrier, no byte
  double one_byte = 0.0;   // noise: bytes, but no packet
  double bad_crc = 0.0;    // noise: a whole frame whose CRC failed
  double Nothing() const { return 1.0 - packet - zero_byte - one_byte - bad_crc; }
};

struct DecodeTable {
  std::string profile;  // "nava" or "room" (nava_modem::ProfileName)
  int packets = 0;      // measured per cell
  double whine_hz = 0.0;
  double band_low_hz = 0.0, band_high_hz = 0.0;
  std::string command;  // how the table was made
  // The rooms it was measured over: a renderer that holds the model against its receiver
  // (scene_render.h) renders the same kind.
  nava_modem::RoomOptions::Model rooms = nava_modem::RoomOptions::Model::kStatistical;
  double lead_s = kTableLeadSeconds;  // s of the disturbance before each packet
  std::vector<double> snr_db, drr_db, rt60;  // each ascending, at least one value
  // How much more a whine of fundamental `whine_harm_hz[k]` harms the receiver than one at
  // whine_hz of the same power, dB, measured with the renderer's motor whine (its harmonics)
  // (whine_harm.h in the tools). Empty: no curve measured; the model then weighs a whine by a
  // rule of thumb. whine_harm_hz ascending, the two the same length.
  std::vector<double> whine_harm_hz, whine_harm_db;
  // Indexed [kind][rt60][drr][snr], every kind of Interference in its enum order.
  std::vector<DecodeOutcome> cells;

  std::size_t Index(Interference kind, std::size_t rt, std::size_t drr, std::size_t snr) const;
  DecodeOutcome& At(Interference kind, std::size_t rt, std::size_t drr, std::size_t snr) {
    return cells.at(Index(kind, rt, drr, snr));
  }
  const DecodeOutcome& At(Interference kind, std::size_t rt, std::size_t drr, std::size_t snr) const {
    return cells.at(Index(kind, rt, drr, snr));
  }
  // Sizes `cells` for the axes (all zero).
  void Resize();
  // Linear interpolation in SNR, DRR and RT60, clamped at each axis' ends (beyond the loudest
  // SNR measured the receiver does no better; beyond the quietest, no worse).
  DecodeOutcome Lookup(Interference kind, double snr_db, double drr_db, double rt60) const;
  // whine_harm_db at `hz`, linear between the measured frequencies, held beyond them. Throws
  // std::logic_error without a curve.
  double WhineHarmDb(double hz) const;
};

// Reads a table. Throws grid::InputError naming the file, the field and the value: a missing or
// malformed field, axes that are empty or not ascending, a fraction outside [0, 1] or a cell
// whose fractions sum above 1, a missing kind, or (when `expected_profile` is not empty) a table
// for another profile.
DecodeTable LoadDecodeTable(const std::string& path, const std::string& expected_profile = "");
// Writes a table that LoadDecodeTable reads back equal (fractions to 4 decimals). Throws
// std::runtime_error naming the path when it cannot be written.
void SaveDecodeTable(const std::string& path, const DecodeTable& table);

// Where the shipped table of a profile is: tables/PROFILE.yaml in the package's share folder
// (package_data; the source tree's audio_propagation/tables/ seen from the build tree). Throws
// std::runtime_error when the share folder cannot be found.
std::string ShippedDecodeTable(const std::string& profile);

}  // namespace audio_propagation
