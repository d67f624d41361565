#pragma once

// Room impulse responses like measured ones: what the statistical response of
// room_impulse_response.h lacks, found by holding it against the rooms of ../shared/realrooms
// (response_features.h reads both):
// - the loudspeaker's and the microphone's colouring: a high-pass (a small speaker has no bass)
//   and resonances of a few dB, minimum phase, over the whole response (measured rooms: the
//   third-octave levels in 630-5000 Hz spread 2.7-7.6 dB; the statistical response's 0.2-0.8),
//   and a directivity of its own on the direct sound (3.7-11 dB measured; 0). The colouring
//   spreads the direct sound over 0.2-1 ms, as measured, and makes one of nava's tones several
//   dB weaker than the other (measured 2300 over 3700 Hz: -8 to +10 dB; statistical: -2 to 0);
// - the first reflections at geometric delays: the image sources of the floor, the ceiling and
//   four walls of a box room, for the loudspeaker's and the microphone's heights. Unless given,
//   the heights are drawn as the measured rooms' were (a loudspeaker on a stand, a microphone or
//   a dummy head at a listener's height: 1 to 1.7 m), the rooms the model is checked against.
//   A robot's speaker and microphone near the floor hear the floor's reflection within a
//   fraction of a millisecond of the direct sound, which cuts a notch into the band that moves
//   with the distance: drawn at 0.15-0.6 m, one of nava's two tones then has a direct sound
//   far weaker against its own reverberation than in any measured room (the two tones' DRRs
//   5-95 %: 12 dB apart either way; measured rooms: -5 to +7 dB), and a nava table over such
//   rooms predicted 22 points fewer packets than the measured rooms decode. No measured room
//   here was taken at a robot's height to say which is right for robots;
// - absorption that rises with frequency: the diffuse tail decays in five bands, each with its
//   own T60 = rt60 x (f / 1500 Hz)^-a, a drawn from 0.15 to 0.3 (measured: T30 at 4 kHz over
//   T30 at 1 kHz 0.68-0.77; a stone basement 1.1), and builds up over the room's mixing time
//   (about sqrt(V) ms) from the first reflection after the direct sound's 2.5 ms (a wall's or
//   the ceiling's), but not before 5 ms.
// The room's size follows from its reverberation and its critical distance (Sabine: a critical
// distance of 0.057 sqrt(V / RT60) m); the critical distance is drawn from 0.7 to 4 m and the
// distance between the robots then follows from the DRR, unless the geometry gives it.
// The DRR and RT60 are read in 600-5400 Hz by the definitions of ../shared/realrooms/README.md
// (MeasureResponse): the reverberant part is scaled until the energy within 2.5 ms of the direct
// sound's peak over the energy after it is the asked DRR, and the tail's decays until its T30 is
// the asked RT60. Where the direct sound is the response's largest peak (measured rooms: DRR above
// about -12 dB), MeasureResponse reads the asked DRR; far below, it reads about the largest peak
// of the reverberation and so a higher DRR than the room's. No ROS.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace nava_modem {

// Where the sender and the listener stand, as far as a renderer knows it; 0: unknown, drawn.
struct ResponseGeometry {
  double distance_m = 0.0;           // 0: from the DRR and the drawn critical distance
  double source_height_m = 0.0;      // 0: drawn from 1 to 1.7 m (as the measured rooms' were)
  double microphone_height_m = 0.0;  // 0: drawn from 1 to 1.7 m
  double ceiling_m = 0.0;            // 0: drawn from 2.5 to 4 m
};

// The direct sound is at index kMeasuredLikeDelay (so that the reflections the floor puts a few
// samples after it, placed between samples, keep their whole pulse): a renderer takes the
// response's largest peak as where the sound arrives, as for a measured response.
constexpr std::size_t kMeasuredLikeDelay = 16;

// The response for `rt60` (s, above 0, at most 10) and `drr_db` (-40..40) at `sample_rate`
// (above 2 x 5400 Hz); the same arguments give the same response. Length: the delay plus
// max(1.2 x rt60, 45 ms). Throws std::invalid_argument for arguments out of range (naming them)
// and for a geometry with a negative length, a height at or above its ceiling, or a distance no
// longer than the heights' difference.
std::vector<float> MeasuredLikeResponse(double rt60, double drr_db, double sample_rate, std::uint32_t seed,
                                        const ResponseGeometry& geometry = {});

}  // namespace nava_modem
