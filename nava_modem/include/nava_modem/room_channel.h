#pragma once

// The room channel: turns a clean modem recording into what a robot's microphone in a real
// room hears, to test the receivers on realistic signals (nava_room, nava_bench --rooms, the
// scene renderer). No ROS.
//
// The chain, in order:
//  1. clock offset: the sender's sound card runs fast or slow, so everything it plays is
//     resampled (libsamplerate) by 1 / (1 + clock_offset): +1 % moves 3000 Hz to 3030 Hz and
//     shortens the sound by 1/1.01;
//  2. spectral tilt (TiltGainDb) and 3. the room's impulse response (room_impulse_response.h,
//     or a measured one: measured_response.h), both applied as one product of spectra in one
//     FFT; the output is longer than the input by the impulse response (its reverberation tail);
//  4. noise (white or pink), the interferer (looped to cover the output, not reverberated: it
//     stands for whatever the microphone picks up besides the modem, room and all) and the
//     motor whine, each scaled to its ratio to the modem signal's level (below);
//  5. the sum scaled so that its peak is 0.9 of full scale.
//
// Levels: the signal power is the mean of the squared rendered modem signal (after steps 1-3)
// over the samples where the clean signal sounds (SoundingSamples of the clock-shifted clean
// signal: its 10 ms RMS envelope at least a tenth, -20 dB, of the envelope's peak; moved by a
// measured response's delay to its largest peak, where the packet is heard), so that the
// silences between packets do not count and the reverberation during a packet does. The noise,
// interferer and whine powers are their mean squares over the whole output. Then
// SNR = 10 log10(signal power / noise power), likewise SIR and the whine's SIR.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nava_modem/measured_like_response.h"

namespace nava_modem {

struct RoomOptions {
  double rt60 = 0.0;    // s, mid-frequency reverberation time; 0 = no reverberation (the direct sound only)
  double drr_db = 0.0;  // direct-to-reverberant energy ratio of the impulse response, dB
  // The room's response for rt60 and drr_db: the statistical one (room_impulse_response.h) or one
  // like measured rooms' (measured_like_response.h: the transducers' colouring, the floor's and
  // walls' reflections, absorption rising with frequency; its DRR read in 600-5400 Hz as
  // ../shared/realrooms/README.md reads it; the sample rate then above 10800 Hz).
  // measured: a measured room, given as `response` (moved to the figures asked: moved_rooms.h);
  // the name a decode table measured over such rooms carries.
  enum class Model { kStatistical, kMeasuredLike, kMeasured };
  Model model = Model::kStatistical;
  // Where the sender and the listener stand, for the measured-like model (unknown parts drawn).
  ResponseGeometry geometry;
  // A measured impulse response at the render's sample rate (LoadImpulseResponse), used as given
  // in place of the statistical room: rt60 and drr_db must then be 0. Its own delay is kept.
  std::vector<float> response;
  // Gain at tilt_high_hz minus gain at tilt_low_hz (negative: highs weaker): 0 dB up to
  // tilt_low_hz, tilt_db from tilt_high_hz up, linear in log-frequency between.
  double tilt_db = 0.0;
  double tilt_low_hz = 2300.0, tilt_high_hz = 3700.0;
  // Fraction: +0.01 = the sender's sound card runs 1 % fast (all frequencies 1 % higher,
  // durations 1 % shorter).
  double clock_offset = 0.0;
  enum class Noise { kNone, kWhite, kPink };
  Noise noise = Noise::kNone;
  double snr_db = 30.0;  // of the noise, when noise != kNone
  double sir_db = 0.0;   // of the interferer, when one is given
  // Motor whine (noise_sources.h MotorWhine): 0 = none; else a tone with harmonics at 2x and 3x
  // (weaker), amplitude-modulated at whine_am_hz (depth 50 %) and wandering ~1 % in frequency.
  double whine_hz = 0.0;
  double whine_sir_db = 0.0;
  double whine_am_hz = 5.0;
  std::uint32_t seed = 1;
};

// A field of RoomOptions out of its range: what() is one line naming the field, the value and
// what was expected; field() is the field's name (so a tool can name its own flag).
class RoomOptionError : public std::invalid_argument {
 public:
  RoomOptionError(const std::string& field, const std::string& message)
      : std::invalid_argument(message), field_(field) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// The models by name: "statistical", "measured-like" and "measured" (the tools' --response, a
// table's rooms).
std::optional<RoomOptions::Model> ParseRoomModel(const std::string& name);
const char* RoomModelName(RoomOptions::Model model);
inline const char* kRoomModelNames = "statistical, measured-like or measured";

// Throws RoomOptionError (a std::invalid_argument) for: sample_rate not above 0; rt60 < 0 or
// > 10 s; |drr_db| > 40; the measured-like model at a sample rate not above 10800 Hz; a geometry
// with the statistical model; a response that is silent or not finite, or given with rt60 or
// drr_db; the measured model without a response; |tilt_db| > 40; tilt_low_hz <= 0 or >= tilt_high_hz; |clock_offset| > 0.05; snr_db, sir_db or whine_sir_db outside -60..100; whine_hz < 0 or whose 1 % wander would
// reach Nyquist (whine_hz >= Nyquist / 1.01); whine_am_hz < 0 or > 100; an unknown noise kind.
void ValidateRoomOptions(const RoomOptions& o, double sample_rate);

// What RenderRoom did, for reports (nava_room's summary line).
struct RoomRenderInfo {
  // Of the impulse response used (+inf without a room): the statistical response's DRR
  // (MeasureDrrDb), a measured one's in the modems' band (MeasureResponse).
  double measured_drr_db = 0.0;
  double signal_power = 0.0;       // the level definition's signal power, before output_gain
  double sounding_fraction = 0.0;  // of the clean (clock-shifted) samples that count as sounding
  double noise_rms = 0.0;          // RMS of the added noise, before output_gain (0 = none)
  double interferer_gain = 0.0;    // applied to the interferer's samples, before output_gain
  double whine_rms = 0.0;          // RMS of the added whine, before output_gain
  double output_gain = 1.0;        // the final scaling that puts the peak at 0.9
};

// The microphone's signal for `clean` recorded at `sample_rate` (the chain above).
// `interferer` is at `sample_rate` (empty = none) and is looped to cover the output.
// Throws std::invalid_argument for bad options, or when a level is asked relative to a silent
// clean signal, or for a silent interferer. An empty `clean` gives an empty output.
std::vector<float> RenderRoom(const std::vector<float>& clean, double sample_rate, const RoomOptions& options,
                              const std::vector<float>& interferer = {}, RoomRenderInfo* info = nullptr);

// Resampling with libsamplerate (SRC_SINC_BEST_QUALITY), ratio = output rate / input rate, from
// 1/256 to 256 (else std::invalid_argument). Used for the clock offset and for interferers
// recorded at another rate.
std::vector<float> Resample(const std::vector<float>& in, double ratio);

// A sound file (ReadAudioFile: mixed to mono) resampled to `rate`, as interferers recorded at
// another rate are used. Throws as ReadAudioFile and Resample do.
std::vector<float> ReadAudioAt(const std::string& path, double rate);

// The tilt's gain at `hz`, dB (0 below tilt_low_hz, tilt_db above tilt_high_hz).
double TiltGainDb(const RoomOptions& o, double hz);

// Which samples of `x` sound, per the level definition above: the RMS over a centred window of
// kSoundingWindowS is at least kSoundingThreshold of that RMS's peak. All false for silence.
std::vector<bool> SoundingSamples(const std::vector<float>& x, double sample_rate);
constexpr double kSoundingWindowS = 0.010;
constexpr double kSoundingThreshold = 0.1;  // amplitude ratio: -20 dB
constexpr double kRoomPeak = 0.9;            // the output's peak, of full scale

}  // namespace nava_modem
