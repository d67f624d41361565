#pragma once

// A statistical model of a room's impulse response, for rendering what a robot's microphone
// hears (room_channel.h) and, later, whole scenes.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nava_modem/noise_sources.h"

namespace nava_modem {

// The model, from index 0:
// - the direct sound: 1 at index 0;
// - kEarlyReflections early reflections at random delays from 5 to 40 ms with random signs and
//   amplitudes (uniform 0.4..1 times the decay envelope), together 25 % of the reverberant energy;
// - a diffuse tail of Gaussian noise from 5 ms (faded in over 5 ms, as reflections thicken),
//   75 % of the reverberant energy, whose amplitude decays as exp(-6.91 t / T60): below
//   kRoomCrossoverHz T60 = rt60, above it T60 = kHighBandDecayRatio x rt60 (air and soft
//   surfaces absorb high frequencies faster). So `rt60` is the mid-frequency reverberation
//   time, the one rooms are usually quoted with and the one in the modems' bands (600-5400 Hz
//   mostly below 4 kHz). The tail is split into the two bands with one FFT.
// - early reflections and tail scaled together so that direct energy / all other energy is
//   exactly drr_db;
// - length max(1.2 x rt60, 45 ms) (beyond 1.2 x rt60 the tail is 72 dB down).
// rt60 == 0 gives {1}: no room, drr_db is not used. The same arguments give the same response.
// Throws std::invalid_argument for rt60 < 0 or > 10, |drr_db| > 40 or a sample rate <= 0.
std::vector<float> RoomImpulseResponse(double rt60, double drr_db, double sample_rate, std::uint32_t seed);

// The length of RoomImpulseResponse's response for rt60 above 0, in samples.
std::size_t RoomResponseSamples(double rt60, double sample_rate);

constexpr int kEarlyReflections = 8;
constexpr double kEarlyShare = 0.25;  // of the reverberant energy; the tail has the rest
constexpr double kRoomCrossoverHz = 4000.0;
constexpr double kHighBandDecayRatio = 0.7;

// The model's two random parts, for renderers that place them themselves (room_array.h puts
// each early reflection at a fractional, per-microphone delay and gives every microphone its own
// tail). RoomImpulseResponse draws the reflections and then the tail from one RandomSource
// (seed, kImpulseResponseStream).

// One early reflection: its delay after the direct sound and its amplitude before the response's
// scaling (sign x spread x the decay envelope counted from the first reflection).
struct EarlyReflection {
  double delay_s = 0.0;
  double amplitude = 0.0;
};

// kEarlyReflections reflections as above; rt60 above 0.
std::vector<EarlyReflection> DrawEarlyReflections(double rt60, RandomSource& random);

// The diffuse tail as above, n samples from the direct sound (index 0), before scaling: zero
// before 5 ms; rt60 above 0.
std::vector<double> DiffuseTail(std::size_t n, double rt60, double sample_rate, RandomSource& random);

// One band of a diffuse tail: the frequencies from the band before's top (0 for the first) up to
// top_hz, decaying by 60 dB in t60_s.
struct TailBand {
  double top_hz;
  double t60_s;
};

// Gaussian noise of length n (from one RandomSource, one FFT) split into `bands` (ascending tops;
// the last's top above the Nyquist frequency to take every bin), each decaying at its own rate
// from start_s on, faded in with a raised cosine over fade_s (above 0). DiffuseTail is this with
// two bands split at kRoomCrossoverHz, from kTailStartS. Throws std::invalid_argument for no band,
// a T60 not above 0, tops not ascending, fade_s not above 0 or start_s below 0.
std::vector<double> BandedTail(std::size_t n, const std::vector<TailBand>& bands, double start_s, double fade_s,
                               double sample_rate, RandomSource& random);

// Throws std::invalid_argument, naming the argument, for rt60 < 0 or > 10, |drr_db| > 40 or a
// sample rate not above 0 (the arguments every room response takes).
void ValidateRoomResponseArguments(double rt60, double drr_db, double sample_rate);

// Direct-to-reverberant ratio of a response whose direct sound is at index 0, in dB
// (energy of index 0 over the energy of everything after it); +infinity when nothing follows.
double MeasureDrrDb(const std::vector<float>& response);

}  // namespace nava_modem
