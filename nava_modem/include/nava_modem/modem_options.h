#pragma once

#include "nava_modem/crc16.h"

namespace nava_modem {

// The physical layer of a Nava link: binary FSK at audio frequencies. Defaults as the thesis's
// robots: MARK (1) 2300 Hz, SPACE (0) 3700 Hz, 300 bits/s.
struct ModemOptions {
  double mark_hz = 2300.0;
  double space_hz = 3700.0;
  double baud = 300.0;           // bits per second
  double sample_rate = 48000.0;  // Hz: 16000, 44100 and 48000 are the usual ones
  double amplitude = 0.5;        // of full scale; <= 0.5 leaves room for mixes not to clip
  // Frequency changes between bits ramp smoothly over this fraction of a bit (raised cosine),
  // keeping the phase continuous, so that the spectrum stays narrow and the speaker quiet.
  double transition = 0.15;
  CrcVariant crc = CrcVariant::kCcittFalse;
};

// The sample rates (Hz) any profile and any audio device of the project may run at; a profile
// may need more (the room profile's band: ValidateRoomRate).
inline constexpr double kMinSampleRate = 4000.0;
inline constexpr double kMaxSampleRate = 384000.0;

// Throws std::invalid_argument "<what> <rate> Hz: expected 4000 to 384000" outside that range.
void ValidateSampleRate(const char* what, double sample_rate);
// Throws std::invalid_argument "amplitude <value>: expected above 0 and at most 1 (full scale)".
void ValidateAmplitude(double amplitude);

// Throws std::invalid_argument naming the value when the options are impossible: MARK equal to
// SPACE, a tone at or above Nyquist, a bit rate too high for the sample rate or for the tone
// spacing, an amplitude outside (0, 1].
void ValidateModemOptions(const ModemOptions& options);

// Samples per bit (not necessarily whole: 147 at 44.1 kHz, 53.3 at 16 kHz and 300 bits/s).
inline double SamplesPerBit(const ModemOptions& o) { return o.sample_rate / o.baud; }

}  // namespace nava_modem
