#pragma once

// A measured room moved to other figures: its reverberation made to decay faster and stand at
// another level under its direct sound, the pattern of its reflections kept. Decode tables
// measured over such rooms carry real rooms' reflections to every RT60 and DRR of their axes,
// where the renderer's rooms (measured_like_response.h) carry only what was fitted of them: nava
// decodes some 20 points more in measured rooms than in rendered ones of the same RT60 and DRR,
// and what decides a packet's fate there is the pattern of the reflections 10 to 50 ms after the
// direct sound (docs/audio_link.md, calibration on measured rooms). No ROS.
#include <cstddef>
#include <vector>

#include "nava_modem/measured_response.h"

namespace nava_modem {

// The room's direct over reverberant energy, dB: the in-band (600-5400 Hz) energy up to
// kDirectHalfWidthS after the direct sound's sample `peak` over the energy after it, each part
// band-passed alone. MeasureResponse's DRR reads the same where the direct sound is the
// response's largest peak, less the little the band's filters spread across the boundary; where
// a reflection is louder (below DRR 0 dB, often) it takes that for the direct sound. What the
// renderer's rooms are drawn at (measured_like_response.h). Throws std::invalid_argument for a
// peak past the response's end.
double DirectOverReverberantDb(const std::vector<float>& response, std::size_t peak, double sample_rate);

// `response` (a measured room at `sample_rate`, its own delay kept) with everything after its
// direct sound multiplied by one decaying exponential, so that MeasureResponse reads `rt60`
// (within kMovedRt60Tolerance where the room's decay allows: it is one line fit to a curve), and
// its reverberation then scaled to a DirectOverReverberantDb of `drr_db`. Only faster: a slower
// decay would lift the measurement's own noise floor into the room. Cut kMovedLengthRt60 x rt60
// after the direct sound (90 dB down). Throws std::invalid_argument for a response without its
// figures (ResponseProblem), an rt60 not finite, not above 0 or above the response's own (naming
// both), or a DRR not finite or beyond +-kMovedMaxDrrDb.
std::vector<float> MovedResponse(const std::vector<float>& response, double sample_rate, double rt60, double drr_db);
// The same, given the response's own figures (MeasureResponse's of `response` at `sample_rate`),
// as a pool of rooms keeps them: a scene moves a room for every link and packet.
std::vector<float> MovedResponse(const std::vector<float>& response, const ResponseMeasures& own, double sample_rate,
                                 double rt60, double drr_db);
constexpr double kMovedRt60Tolerance = 0.03;  // relative
constexpr double kMovedLengthRt60 = 1.5;
constexpr double kMovedMaxDrrDb = 40.0;

}  // namespace nava_modem
