#pragma once

// A statistical model of a room's impulse response, for rendering what a robot's microphone
// hears (room_channel.h) and, later, whole scenes.
#include <cstdint>
#include <vector>

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

constexpr int kEarlyReflections = 8;
constexpr double kRoomCrossoverHz = 4000.0;
constexpr double kHighBandDecayRatio = 0.7;

// Direct-to-reverberant ratio of a response whose direct sound is at index 0, in dB
// (energy of index 0 over the energy of everything after it); +infinity when nothing follows.
double MeasureDrrDb(const std::vector<float>& response);

}  // namespace nava_modem
