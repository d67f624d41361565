#pragma once

#include <cstddef>
#include <vector>

#include "nava_bench_args.h"
#include "tool_args/usage_error.h"

namespace nava_modem::tools {

// A response and its direct sound's sample (MeasureResponse's peak).
struct PeakedResponse {
  std::vector<float> samples;
  std::size_t peak = 0;
};

// The response that is `head`'s up to `at` samples after its direct sound and `tail`'s from
// there on, the two aligned on their direct sounds; the head's part scaled so that its energy in
// 600-5400 Hz is `keep`'s before `at`, the tail's so that it is `keep`'s from `at` on. With `keep`
// one of the two, the splice keeps that room's DRR and reverberant level, and the other room's
// sound in its span. Pure; throws std::invalid_argument for a peak outside its response.
std::vector<float> SpliceResponses(const PeakedResponse& head, const PeakedResponse& tail, const PeakedResponse& keep,
                                   std::size_t at, double sample_rate);

// nava_bench --splice --early A.wav[:K] --late B.wav[:K] --at-ms LIST --out DIR: which span of a
// room's response decides what a receiver makes of it. Writes a.wav and b.wav (the two responses
// at request.sample_rate, mono) and, for each T of request.at_ms, aT_b.wav (A's first T ms, B's
// sound after, at A's energies) and bT_a.wav (B's first T ms, A's sound after, at A's energies),
// and prints each file's RT60 and DRR; `nava_bench --rooms --rir-dir DIR` then decodes packets
// through them. Returns the exit code.
int SpliceTable(const SpliceRequest& request, const multirobot_audio::tools::ToolUsage& usage);

}  // namespace nava_modem::tools
