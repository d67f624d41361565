#pragma once

// How much of a disturbance a robot's carrier sense hears. A robot's MAC reads its receiver's
// level meter, which listens only in the profile's bands (nava: its two tones, each within half
// its bit rate; room: its whole band; taken as the bands the receiver decodes in, ListeningBands,
// though room's meter spans a little more, 500-6000 Hz against 600-5400), and calibrates its threshold on what that meter reads of
// the room's noise. A noise whose power lies mostly outside those bands (a compressor's 400 Hz
// hum, the low formants of speech) raises neither the threshold nor the carrier by its whole
// power. The modem's own packets lie wholly in the bands and count whole. No ROS.
#include "nava_modem/modem_profile.h"
#include "world_sim/acoustics.h"

namespace audio_propagation {

// The share (0 to 1) of a disturbance's full-band power, sampled at `sample_rate`, that lies in
// `profile`'s listening bands (nava_modem::ListeningBands), with ideal band edges. White, pink
// and a whine at `whine_hz` are the renderer's own noises (nava_modem/noise_sources.h); speech
// is the benches' espeak-ng speech (make_speech.sh), whose shares are measured constants. A
// recording has no fixed share: use nava_modem::RecordedNoise::Fraction; kRecording throws
// std::invalid_argument, as does a whine_hz outside (0, sample_rate / 2).
double CarrierShare(world_sim::NoiseKind kind, double whine_hz, nava_modem::Profile profile, double sample_rate);

}  // namespace audio_propagation
