#pragma once

// The room channel (room_channel.h) heard by a microphone array: one channel per microphone, so
// that direction-of-arrival estimators can be tried on rendered rooms. No ROS.
//
// The model, per microphone m at p_m, with the source at distance d and bearing b from the
// array's origin (s = d (cos b, sin b)), r_m = |s - p_m|, c the speed of sound:
//  - the source signal is clock-shifted and tilted once, as in RenderRoom (steps 1-2);
//  - direct sound: delayed by r_m / c and scaled by d / r_m (1/r, relative to the origin, so a
//    microphone at the origin hears it as RenderRoom does). Fractional delays are exact phase
//    ramps on the spectrum, never rounded to samples;
//  - early reflections: RenderRoom's (same delays and amplitudes for the seed, counted from the
//    direct sound's arrival at the origin), each a plane wave from its own random direction u_r,
//    so it reaches microphone m (p_m . u_r) / c earlier than the origin; equal level at every
//    microphone (plane waves have no 1/r);
//  - diffuse tail: the same RT60 and level everywhere, but an independent realisation per
//    microphone (its own seed), so tails are uncorrelated between microphones. A real diffuse
//    field's coherence, sin(kD)/(kD) for spacing D, is not modelled: it matters only for
//    microphones closer than about half a wavelength (6 cm at 3 kHz);
//  - the reverberant part (early + tail) is scaled per microphone so that its energy over the
//    direct energy at the origin is exactly drr_db: every microphone hears the same room, and a
//    channel's own DRR is drr_db + 20 log10(d / r_m);
//  - noise: independent per microphone (its own seed), white or pink;
//  - interferer and whine: each a plane wave from its own bearing (drawn from the seed, uniform
//    over the circle, reported in ArrayRenderInfo): the same far-field wave in every channel,
//    delayed per microphone, not reverberated (as in RenderRoom);
//  - levels: SNR and SIRs per channel, against that channel's own modem signal (its mean square
//    over the sounding samples, the mask shifted to that channel's direct arrival);
//  - one gain for all channels puts the loudest channel's peak at 0.9, so levels between
//    channels stay true.
// Time 0 of the output is when the source starts to play, so the direct sound arrives at
// sample r_m / c x rate, unless a far microphone would hear a reflection's plane wave before
// time 0: then everything is later by lead_s (ArrayRenderInfo).
#include <cstdint>
#include <vector>

#include "nava_modem/microphone2d.h"
#include "nava_modem/room_channel.h"

namespace nava_modem {

struct ArraySource {
  std::vector<Microphone2D> mics;  // at least one, no two at the same place
  double bearing = 0.0;            // rad, CCW from the robot's +x (forward) axis
  double distance = 2.0;           // m, from the array's origin: above 0, at most kMaxSourceDistance
  double speed_of_sound = 343.0;   // m/s
};

constexpr double kMaxSourceDistance = 100.0;  // m: a room, not a field
constexpr double kMinMicDistance = 0.01;      // m: nearer, 1/r would blow the level up

// Throws RoomOptionError (field "mics", "bearing", "distance" or "speed_of_sound") for: no
// microphones, a coordinate not finite, two microphones at the same place, a bearing not
// finite, a distance not above 0 or above kMaxSourceDistance, a source nearer than
// kMinMicDistance to a microphone, a speed of sound not above 0. what() is one line; for "mics"
// it names the microphones (numbered from 1) but not the field, so that a tool can put its own
// flag and the list as typed before it.
void ValidateArraySource(const ArraySource& source);

struct ArrayChannelInfo {
  double direct_delay_s = 0.0;  // when the direct sound arrives, from the output's start
  double direct_gain = 1.0;     // d / r_m
  double drr_db = 0.0;          // of this channel's response (+inf without a room)
  double signal_power = 0.0;    // the level definition's, before output_gain
  double noise_rms = 0.0;       // before output_gain (0 = none)
  double interferer_gain = 0.0; // applied to the interferer's samples, before output_gain
  double whine_rms = 0.0;       // before output_gain
};

struct ArrayRenderInfo {
  std::vector<ArrayChannelInfo> channels;
  double sounding_fraction = 0.0;   // of the clean (clock-shifted) samples
  double interferer_bearing = 0.0;  // rad, where the interferer comes from
  double whine_bearing = 0.0;       // rad, where the whine comes from
  double lead_s = 0.0;              // added to every arrival (see above; usually 0)
  double output_gain = 1.0;         // the one gain that puts the loudest peak at 0.9
};

// Channel m is microphone m's signal for `clean` at `sample_rate` (the model above); all
// channels have the same length. Throws RoomOptionError for bad options or source (a measured
// response among them: it is one microphone's), and
// std::invalid_argument as RenderRoom does. An empty `clean` gives empty channels.
std::vector<std::vector<float>> RenderRoomArray(const std::vector<float>& clean, double sample_rate,
                                                const RoomOptions& options, const ArraySource& source,
                                                const std::vector<float>& interferer = {},
                                                ArrayRenderInfo* info = nullptr);

}  // namespace nava_modem
