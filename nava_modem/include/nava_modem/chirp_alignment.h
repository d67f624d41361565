#pragma once

// Where the `room` profile's chirps lie, read off the chirp detector's matched-filter envelope
// after it has found them: a packet's second chirp placed against its first to a fraction of a
// sample (their distance is the sender's clock), and a chirp too faint for the detector looked
// for where it must be. No ROS.
#include <cstdint>
#include <optional>
#include <vector>

#include "nava_modem/chirp_detector.h"

namespace nava_modem {

// The envelope lined up around a chirp: from kAlignBeforeS before its start to kAlignAfterS
// after (the direct sound and the early reflections), at lags up to kAlignReachS either way (a
// late reflection's delay).
constexpr double kAlignBeforeS = 0.010, kAlignAfterS = 0.050, kAlignReachS = 0.045;

// Samples of envelope the detector must have computed past a chirp's start before AlignedPosts
// can place a chirp there.
std::int64_t AlignmentLookahead(double sample_rate);

// Where a chirp lies near `around` (samples), by lining up `anchor`'s envelope (its direct sound
// and reflections) with the envelope there, at lags up to `reach_s` either way: the best lag,
// then (picks 2) the best one at least a millisecond from it, each to a fraction of a sample.
std::vector<double> LineUpChirp(const ChirpDetector& detector, double sample_rate, const ChirpPeak& anchor, double around,
                                double reach_s, int picks);

// A chirp's envelope as LineUpChirp lines it up (from kAlignBeforeS before its start to
// kAlignAfterS after), kept for lining up a chirp heard after the detector has forgotten this one
// (a long frame's last chirp, a minute after the one before it).
struct ChirpShape {
  double sample = 0.0;  // the chirp's start, as found
  std::vector<double> envelope;
};
ChirpShape ShapeOf(const ChirpDetector& detector, double sample_rate, const ChirpPeak& anchor);
// LineUpChirp against a kept shape.
std::vector<double> LineUpShape(const ChirpDetector& detector, double sample_rate, const ChirpShape& shape, double around,
                                double reach_s, int picks);

// Where a packet's second chirp starts, given its first: at the two best alignments of their
// envelopes (LineUpChirp within kAlignReachS), then at the peaks' own distance. In a reverberant
// room the strongest peak can be the direct sound in one chirp and a reflection in the other,
// but the room (and so the envelope's pattern of direct sound and reflections) is the same for
// both.
std::vector<double> AlignedPosts(const ChirpDetector& detector, double sample_rate, const ChirpPeak& pre, const ChirpPeak& post);

// The envelope's strongest output between two sample positions, as a chirp, if it stands out
// from the mean output before them 4 times (far below the detector's own threshold: the window
// is narrow, and the CRC judges what is decoded); nothing where the envelope is not known yet.
std::optional<ChirpPeak> StrongestChirpIn(const ChirpDetector& detector, double sample_rate, double from, double to);

}  // namespace nava_modem
