#pragma once

// A noise as a modem's receiver hears it: its power and how that power spreads over frequency,
// read from a recording (a fan, a corridor, a kitchen), so that a recorded noise can be weighed
// against the white noise a decode table was measured with. What counts is the power in the
// bands the profile's receiver listens to: nava's two tones (each within half its bit rate),
// the room profile's whole band. A recording whose power lies in those bands hurts more than
// white noise of the same full-band level; one that rumbles below them, less. No ROS.
#include <cstddef>
#include <utility>
#include <vector>

#include "nava_modem/modem_profile.h"

namespace nava_modem {

// Frequency bands, Hz, [low, high).
using Bands = std::vector<std::pair<double, double>>;

// The bands `profile`'s receiver listens in, with the thesis's tones for nava.
Bands ListeningBands(Profile profile);

class RecordedNoise {
 public:
  // Welch's method: Hann windows of kWindow samples, half overlapping, their power spectra
  // averaged. Throws std::invalid_argument for a sample rate not above 0, a recording shorter
  // than one window, a sample that is not finite, or a silent recording.
  RecordedNoise(const std::vector<float>& samples, double sample_rate);

  static constexpr std::size_t kWindow = 4096;

  double sample_rate() const { return sample_rate_; }
  double power() const { return power_; }  // mean square over the whole band
  // The fraction of the power within `bands` (the part of a bin inside a band counts).
  double Fraction(const Bands& bands) const;

 private:
  double sample_rate_;
  double power_ = 0.0;
  std::vector<double> density_;  // per bin of sample_rate / kWindow Hz, summing to 1
};

// The fraction of white noise's power, sampled at `sample_rate`, within `bands`.
double WhiteFraction(const Bands& bands, double sample_rate);

// What to add to a recording's full-band SNR to read it as white noise sampled at `white_rate`
// (the decode table's rate) with the same power in `bands`: 10 log10(white's fraction / the
// recording's). Positive for a noise that mostly misses the bands.
double WhiteEquivalentOffsetDb(const RecordedNoise& noise, const Bands& bands, double white_rate);

// How a noise's power spreads over a receiver's time-frequency cells: each cell `cell_seconds`
// long and `cell_hz` wide, tiling `bands` (Hann-windowed frames, back to back). Returns
// [frame][cell] powers over the mean of all cells. Throws std::invalid_argument for a rate or
// cell not above 0, a recording shorter than 4 frames, no cell below the Nyquist frequency, or
// silence in the bands.
std::vector<std::vector<double>> CellPowers(const std::vector<float>& samples, double sample_rate,
                                            const Bands& bands, double cell_seconds, double cell_hz);

// The exponential effective SNR mapping (EESM, as link abstractions of coded OFDM use it): a
// code spread over cells of SNR g_i decodes about as one over cells all at
// g_eff = -beta ln(mean exp(-g_i / beta)). `cells` are the noise's powers over its mean power,
// so g_i = g / cell; `snr_db` is g and `beta_db` beta, in dB. Below beta a cell's worth grows
// with its SNR, far above it the cell counts as sure: quiet cells help, but only as far as the
// cells the noise buries let them.
double EffectiveSnrDb(const std::vector<double>& cells, double snr_db, double beta_db);

// A recording weighed for a profile's receiver against the decode table's white noise, sampled
// at `white_rate`:
// - nava: its power in the two tones' bands (WhiteEquivalentOffsetDb). Uncoded: every bit must
//   be right, so a burst on a tone costs the packet, and the mean power is what counts.
// - room: that over its band, then per packet: the cells one packet's 42 symbols use (40 ms each
//   in its hop's 400 Hz sub-band), packets laid at kPacketWindows places along the recording,
//   each read by EffectiveSnrDb against what white noise's own cells give. Its convolutional
//   code spreads each bit over symbols in all 12 sub-bands, so a noise that comes and goes
//   (running water, dishes, speech) or piles into part of the band harms it less than white
//   noise of its power, and a rare burst costs only the packets it falls on.
// Held against the real receivers through measured rooms (decode_table_bench --calibrate
// --noise-file; docs/audio_link.md). Throws what RecordedNoise and CellPowers throw, and, for
// room, std::invalid_argument for a recording sampled below 10800 Hz (its band reaches 5400 Hz).
class RecordingWeight {
 public:
  RecordingWeight(const std::vector<float>& samples, double sample_rate, Profile profile, double white_rate);

  // What to add to a full-band SNR to read the recording as white noise of its power in the bands.
  double in_band_offset_db() const { return in_band_offset_db_; }
  double in_band_fraction() const { return in_band_fraction_; }
  // The table's white-noise SNR that harms each packet as this recording does, one per packet
  // place (one alone for nava), when `share` (0..1] of the noise in the bands is the recording
  // and the rest is steady, their sum read as white noise at `white_snr_db`.
  std::vector<double> TableSnrsDb(double white_snr_db, double share = 1.0) const;

  static constexpr std::size_t kPacketWindows = 48;
  // EESM's beta for room's receiver in the tables' SNR (full band at 48 kHz), fitted on
  // measured rooms in running water and checked in speech (docs/audio_link.md).
  static constexpr double kRoomBetaDb = -11.0;

 private:
  double in_band_offset_db_ = 0.0;
  double in_band_fraction_ = 0.0;
  std::vector<std::vector<double>> packets_;  // room: each packet place's cells; empty for nava
  std::vector<double> white_cells_;           // room: white noise's cells, as CellPowers reads them
};

}  // namespace nava_modem
