#pragma once

// The room channel's disturbances that are not the modem signal: white and pink noise and a
// robot's motor whine. Each is deterministic for its seed; levels are set by the caller, so
// each comes out at mean power 1.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace nava_modem {

// Uniform and Gaussian numbers from mt19937 with our own transforms: the standard library's
// distributions differ between implementations, and a seed should give the same room on any.
// `stream` keeps the room's separate random uses (impulse response, noise, whine) apart.
class RandomSource {
 public:
  RandomSource(std::uint32_t seed, std::uint32_t stream);
  double Uniform();   // in (0, 1)
  double Gaussian();  // mean 0, variance 1 (Box-Muller)

 private:
  std::mt19937 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

// Streams of RandomSource for the room's random parts. kArrayStream: the microphone array's
// directions (room_array.h), apart from the mono room's so that the same seed keeps its room.
enum RandomStream : std::uint32_t { kImpulseResponseStream = 1, kNoiseStream = 2, kWhineStream = 3, kArrayStream = 4 };

std::vector<double> WhiteNoise(std::size_t n, std::uint32_t seed);

// Power spectral density proportional to 1/f from 20 Hz up (flat below, nothing at DC):
// Gaussian white noise shaped by 1/sqrt(f) in one FFT, so it is exactly pink, not a filter's
// approximation.
std::vector<double> PinkNoise(std::size_t n, double sample_rate, std::uint32_t seed);

// A motor's whine: a tone at `hz` with harmonics at 2x (-6 dB) and 3x (-12 dB), amplitude
// modulated at `am_hz` with depth 50 % (0 = steady), and its frequency wandering slowly and
// randomly by up to about 1 % (a sum of three sines below 0.7 Hz with random phases, as a motor's
// speed drifts under load). Harmonics whose wandering would reach Nyquist are left out.
std::vector<double> MotorWhine(std::size_t n, double sample_rate, double hz, double am_hz, std::uint32_t seed);

}  // namespace nava_modem
