#pragma once

// Two room impulse responses joined at a time after their direct sounds: which span of a
// response decides what a receiver makes of it (nava_bench --splice). No ROS.
#include <cstddef>
#include <vector>

namespace nava_modem {

// A response and its direct sound's sample (MeasureResponse's peak).
struct PeakedResponse {
  std::vector<float> samples;
  std::size_t peak = 0;
};

// The response that is `head`'s up to `at` samples after its direct sound and `tail`'s from
// there on, the two aligned on their direct sounds (the output's direct sound lies
// min(head.peak, keep.peak) samples in). Each part is scaled to `keep`'s energy in 600-5400 Hz
// over the same span: the head's over everything before `at`, the tail's from `at` to where the
// shorter of `tail` and `keep` ends (so that a longer file's noise floor does not count). The
// direct sound's share of the head's energy is the head's own, so the splice's DRR and RT60 are
// not `keep`'s in general: read them. Throws std::invalid_argument for a peak outside its
// response, and for a part with no sound in its span (`at` past a response's end).
std::vector<float> SpliceResponses(const PeakedResponse& head, const PeakedResponse& tail, const PeakedResponse& keep,
                                   std::size_t at, double sample_rate);

}  // namespace nava_modem
