#pragma once

// What a room impulse response holds beyond its RT60 and DRR, read in the modems' band: the
// features that tell a measured response (a real loudspeaker or clap, a real microphone, a floor
// and walls at real distances) from a statistical one, and that a modem's receiver feels. They
// let the renderer's responses be held against measured ones (room_impulse_response.h). No ROS.
#include <vector>

#include "nava_modem/measured_response.h"

namespace nava_modem {

// The end of the early part after the direct sound: the floor's, walls' and ceiling's first
// reflections in a room of a few metres.
constexpr double kEarlyEndS = 0.050;
// The end of the reverberation's onset: what of it arrives within two or three of nava's 3.3 ms
// bits of the direct sound, where its equaliser can still use it.
constexpr double kOnsetEndS = 0.010;
// Third-octave bands whose centres lie in the modems' band (630 Hz to 5 kHz): where the colouring
// is read.
constexpr int kColourBands = 10;

struct ResponseFeatures {
  ResponseMeasures measures;  // RT60, DRR, the direct sound's peak (MeasureResponse)
  // The direct sound's duration: the RMS spread of its energy (within kDirectHalfWidthS of the
  // peak) about the peak, ms. A single sample through the band's filters gives about 0.2 ms.
  double direct_spread_ms = 0.0;
  // Energy from kDirectHalfWidthS to kEarlyEndS after the peak over the direct sound's, dB.
  double early_db = 0.0;
  // Energy from kDirectHalfWidthS to kOnsetEndS after the peak over all the energy after
  // kDirectHalfWidthS, dB (at most 0): how soon the reverberation comes, whatever the DRR. A room
  // whose reverberation builds up slowly (a hall, or a renderer's room built up over its mixing
  // time) has little there; a small, hard room a good part.
  double onset_db = 0.0;
  // The reverberation's early decay over the RT60: the decay time read from the reverberation's
  // own Schroeder curve (everything after kDirectHalfWidthS) between 0 and -10 dB, extended to
  // 60 dB, over measures.rt60_s (T30, or T20). The curve is read without subtracting a noise
  // floor (its first 10 dB stand well over any usable response's). About 1 where the tail decays
  // as one exponential (the
  // renderers' rooms: 0.9-1.1); below 1 where it falls fast at first and slowly later, as in many
  // measured rooms (0.6-0.7 in a lime kiln, a small TV room, a car park). It tells such rooms
  // from the renderer's, though it predicts little of what nava decodes in them
  // (docs/audio_link.md, calibration on measured rooms). NaN without an RT60.
  double reverb_edt_ratio = 0.0;
  // The strongest reflection within the early part: its delay after the peak (ms) and its level
  // over the direct sound's peak level (dB), both from the 0.5 ms energy envelope.
  double strongest_early_ms = 0.0;
  double strongest_early_db = 0.0;
  // The third-octave levels (dB, energy per Hz, relative to their mean) of the whole response
  // and of the direct sound alone (Hann window over its +-kDirectHalfWidthS): the colouring of
  // the room with the transducers, and of the transducers (and the nearest reflections) alone.
  double band_db[kColourBands] = {};
  double direct_band_db[kColourBands] = {};
  // The standard deviations of those levels, dB: how far from flat each is.
  double colour_db = 0.0;
  double direct_colour_db = 0.0;
  // The whole response's energy within +-150 Hz of `tone_a_hz` over that around `tone_b_hz`, dB
  // (for nava's two tones: a room and its transducers can make one 10 dB weaker than the other).
  double tone_ratio_db = 0.0;
  // T30 in the octave about 4 kHz (2828-5400 Hz) over T30 in the octave about 1 kHz
  // (707-1414 Hz): air and surfaces absorb high frequencies more, so this is below 1 in a
  // measured room. NaN where either octave's decay gives no RT60.
  double decay_ratio = 0.0;
};

// The features of `response` at `sample_rate` (above 2 x kResponseBandHighHz); tone_ratio_db at
// the two tones given. Throws std::invalid_argument as MeasureResponse does, and for a tone whose
// +-150 Hz do not lie between 0 and half the sample rate.
ResponseFeatures MeasureFeatures(const std::vector<float>& response, double sample_rate, double tone_a_hz,
                                 double tone_b_hz);

// The centre (Hz) of colour band k: 630 Hz x 2^(k/3).
double ColourBandHz(int k);

}  // namespace nava_modem
