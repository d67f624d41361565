#pragma once

// Direction of arrival from a microphone array, so that a real reception carries a direction as a
// simulated one does (audio_propagation's microphones).
//
// Method: GCC-PHAT per microphone pair, SRP-PHAT over bearing, in three stages: the band spectra
// (WelchAnalyser, band_spectra.h), each pair's correlation (GccPhat, gcc_phat.h), and the bearing
// search and confidence here.
// - Each channel is cut into segments of about 20 ms (a power of two: 1024 samples at 48 kHz,
//   512 at 16 kHz; Tukey-windowed, not overlapping), at most 8 of them: back to back when they
//   fit, else spread evenly over the samples, which keeps a long signal's variety (the nava
//   packet's two tones and its data bits) at a bounded cost. Each pair's cross-spectrum is
//   averaged over the segments (Welch) and kept only inside [low_hz, high_hz].
// - PHAT: every band bin is normalised to unit magnitude, so the correlation peak is as sharp as
//   the band allows whatever the source's spectrum, and a room's colouring does not widen it.
//   Bins more than 40 dB below the band's strongest cross-power are dropped: with the nava
//   profile's two tones most of the band is noise, and PHAT would otherwise give noise bins the
//   same weight as the tones.
// - The correlation (the inverse FFT of the PHAT spectrum, zero-padded so that a lag step is at
//   most 1/(8 high_hz): a sample at 48 kHz, a quarter at 16 kHz, for a 6 kHz band) is read with
//   a parabola through the peak: sub-sample TDOA (within 0.05 samples in the tests).
// - Bearing, 3 or more microphones not on one line: steered response power, the sum over pairs of
//   each pair's correlation at the delay a far-field source at that bearing gives, on a 1-degree
//   grid, refined by a parabola. Summing correlations (rather than least squares on per-pair
//   TDOA peaks) keeps working when one pair's strongest peak is a reflection or an alias: the
//   other pairs outvote it.
// - Bearing, 2 microphones or all on one line: the same sum over the cosine of the angle to the
//   array's axis. Such an array cannot tell the two sides of its axis apart, so it resolves only
//   which end of the axis the sound comes from: the bearing is the axis direction towards the
//   nearer end (for a pair on the x axis: 0, front, or pi, back, as the simulated
//   "bidirectional" microphone). It is NaN when the delay is under 20 % of the largest (the
//   sound within 11.5 degrees of broadside), where noise decides the sign.
// - Reverberation: the direct sound comes first, so only the first `max_seconds` of the samples
//   given are used; PHAT keeps the diffuse tail, uncorrelated between microphones, from biasing
//   the peak. For the room profile its first chirp (0.12 s, 600-5400 Hz) is best: later parts
//   only add reverberation. For the nava profile the whole packet is best: it opens with 67 ms
//   of SPACE then 67 ms of MARK, single tones whose correlations repeat every 0.27 and 0.43 ms,
//   so its opening alone gives wrong bearings in reverberant rooms (nava_decode uses these
//   settings; the measurements behind them are in docs/audio_link.md, "Direction of arrival").
//
// Spatial aliasing with the nava profile: its energy sits at two tones, 2300 and 3700 Hz
// (wavelengths 15 and 9.3 cm). A pair further apart than half a wavelength (7.5 and 4.6 cm) sees
// each tone's correlation repeat within its range of delays. A square of 0.1 m half-diagonal
// (sides 14 cm, diagonals 20 cm) exceeds both, and the two tones together give the correlation
// 2 cos(2 pi 3000 t) cos(2 pi 700 t), which has a second peak of 59 % of the main one at
// +-0.5 ms, inside the diagonals' +-0.58 ms. The six pairs see these aliases at different
// bearings, so the SRP sum still picks the right bearing in clean air and mostly in reverberant
// rooms, but the margin is small, and the confidence in such rooms is low whether or not the
// bearing is right. The room profile's 600-5400 Hz chirp has no such ambiguity. A nava array
// without aliasing would want spacings under 4.6 cm (delays under 0.13 ms, 6 samples at 48 kHz:
// noisier bearings).
//
// Cost: at most 8 segment FFTs per channel and one inverse FFT per pair, whatever the length
// given (the tests print the time per estimate; docs/audio_link.md compares it with decoding).
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "nava_modem/band_spectra.h"
#include "nava_modem/gcc_phat.h"
#include "nava_modem/microphone2d.h"

namespace nava_modem {

// "x1,y1,x2,y2,..." -> positions; throws std::invalid_argument naming the text and what was
// expected (an odd count, fewer than 2 microphones, a non-number, two microphones at one point).
std::vector<Microphone2D> ParseMicPositions(const std::string& text);

struct DirectionOptions {
  std::vector<Microphone2D> mics;
  double sample_rate = 48000.0;
  double low_hz = 500.0, high_hz = 6000.0;  // the band the GCC uses (the profile's)
  double speed_of_sound = 343.0;            // m/s
  // Only the first this many seconds of the samples given are used: the direct sound arrives
  // first, and it bounds the cost.
  double max_seconds = 0.2;
};

// Throws std::invalid_argument "DirectionOptions: <field> <value>; expected ..." when the options
// are impossible: fewer than 2 microphones, two at one point or one not finite, a non-positive
// rate, speed of sound or max_seconds, a band outside (0, sample_rate / 2] or too narrow for a
// few bins of the analysis.
void ValidateDirectionOptions(const DirectionOptions& options);

struct Direction {
  // rad, CCW from the robot's +x, in (-pi, pi]; NaN when the geometry cannot resolve it (or
  // there is nothing in the band).
  double bearing = std::numeric_limits<double>::quiet_NaN();
  // 0..1: the fraction of the band's cross-power (summed over pairs) that lines up at the delays
  // of the chosen bearing, sum Re(S_ij e^{jwt_ij}) / sum sqrt(S_ii S_jj). 1 for one clean plane
  // wave; near 0 for uncorrelated noise (about 0.25 or less for 0.2 s of it); lowered by
  // reverberation and by noise at the microphones. 0 when the bearing is NaN.
  double confidence = 0.0;
};

class DirectionEstimator {
 public:
  // Throws std::invalid_argument for impossible options (ValidateDirectionOptions).
  explicit DirectionEstimator(const DirectionOptions& options);
  ~DirectionEstimator();
  DirectionEstimator(const DirectionEstimator&) = default;
  DirectionEstimator& operator=(const DirectionEstimator&) = default;

  // The direction of the sound in `count` samples of each channel (channels[i] is mic i).
  // Throws std::invalid_argument when the channel count is not the microphone count.
  Direction Estimate(const std::vector<const float*>& channels, std::size_t count) const;

  // Time difference of arrival (s) at mic j relative to mic i by GCC-PHAT with sub-sample
  // interpolation: > 0 when the sound reaches j later. Searched within +- the array's largest
  // spacing over the speed of sound, plus 2 samples. NaN when nothing is in the band.
  double Tdoa(const float* i, const float* j, std::size_t count) const;

  const DirectionOptions& options() const { return options_; }
  bool collinear() const { return collinear_; }

 private:
  DirectionOptions options_;
  bool collinear_ = false;
  double axis_x_ = 1.0, axis_y_ = 0.0;  // collinear arrays: the unit vector along the line
  WelchAnalyser welch_;                 // the first stage: each channel's band spectra
  GccPhat gcc_;                         // the second: each pair's correlation over lags
  std::vector<double> grid_x_, grid_y_;  // the bearing grid's unit vectors
};

// Whether a pair's (or a collinear array's) `estimate` names the end of its axis (at `axis`
// rad) that a sound from `truth` rad is nearer to: the one bit such an array gives. False for a
// NaN estimate. Bearings in the array's frame.
inline bool SameEndOfAxis(double truth, double estimate, double axis = 0.0) {
  return std::isfinite(estimate) && std::cos(truth - axis) * std::cos(estimate - axis) > 0.0;
}

}  // namespace nava_modem
