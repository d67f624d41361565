#include "audio_propagation/carrier_share.h"

#include <cstdint>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "nava_modem/noise_sources.h"
#include "nava_modem/recorded_noise.h"

namespace audio_propagation {
namespace {

// Long enough for Welch's method to average many windows, short enough to cost milliseconds.
constexpr double kSpectrumSeconds = 4.0;
constexpr std::uint32_t kSpectrumSeed = 1;
constexpr std::size_t kKnownShares = 256;

// The share of make_speech.sh's speech in each profile's bands, read by audio_channel_predict's
// "noise_in_band_fraction" from 120-240 s of it with seeds 1, 3 and 7: nava 0.013-0.017, room
// 0.39-0.48. Speech's power lies mostly below 1 kHz, under room's band and far under nava's tones.
constexpr double kSpeechShareNava = 0.0145;
constexpr double kSpeechShareRoom = 0.45;

double MeasuredShare(const std::vector<double>& samples, double sample_rate, const nava_modem::Bands& bands) {
  const std::vector<float> as_float(samples.begin(), samples.end());
  return nava_modem::RecordedNoise(as_float, sample_rate).Fraction(bands);
}

double ComputeShare(world_sim::NoiseKind kind, double whine_hz, nava_modem::Profile profile, double sample_rate) {
  const nava_modem::Bands bands = nava_modem::ListeningBands(profile);
  const auto n = static_cast<std::size_t>(kSpectrumSeconds * sample_rate);
  switch (kind) {
    case world_sim::NoiseKind::kWhite: return nava_modem::WhiteFraction(bands, sample_rate);
    case world_sim::NoiseKind::kPink:
      return MeasuredShare(nava_modem::PinkNoise(n, sample_rate, kSpectrumSeed), sample_rate, bands);
    case world_sim::NoiseKind::kSpeech: return profile == nava_modem::Profile::kNava ? kSpeechShareNava : kSpeechShareRoom;
    case world_sim::NoiseKind::kWhine:
      return MeasuredShare(nava_modem::MotorWhine(n, sample_rate, whine_hz, 0.0, kSpectrumSeed), sample_rate, bands);
    case world_sim::NoiseKind::kRecording: break;
  }
  throw std::invalid_argument("carrier share: a recording's share is its own (RecordedNoise::Fraction)");
}

}  // namespace

double CarrierShare(world_sim::NoiseKind kind, double whine_hz, nava_modem::Profile profile, double sample_rate) {
  if (kind == world_sim::NoiseKind::kWhine && !(whine_hz > 0.0 && whine_hz < sample_rate / 2.0)) {
    throw std::invalid_argument("carrier share: a whine's frequency must be in (0, " + std::to_string(sample_rate / 2.0) +
                                ") Hz, got " + std::to_string(whine_hz));
  }
  if (kind != world_sim::NoiseKind::kWhine) whine_hz = 0.0;
  // A pure function that costs tens of milliseconds (a pink noise's FFT), asked for again by every
  // model an experiment builds, one a trial: kept once worked out.
  static std::mutex mutex;
  static std::map<std::tuple<int, double, int, double>, double> known;
  const auto key = std::make_tuple(static_cast<int>(kind), whine_hz, static_cast<int>(profile), sample_rate);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = known.find(key); it != known.end()) return it->second;
  }
  const double share = ComputeShare(kind, whine_hz, profile, sample_rate);
  const std::lock_guard<std::mutex> lock(mutex);
  if (known.size() >= kKnownShares) known.clear();  // bounded: worlds have a few whines each
  known.emplace(key, share);
  return share;
}

}  // namespace audio_propagation
