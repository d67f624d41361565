#include "nava_modem/room_array.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <sstream>

#include "nava_modem/math_constants.h"
#include "nava_modem/noise_sources.h"
#include "nava_modem/real_fft.h"
#include "nava_modem/room_impulse_response.h"

namespace nava_modem {
namespace {

using Spectrum = std::vector<std::complex<double>>;

// Padding beyond the output in the big FFT: the zero-phase tilt and the fractional delays' sinc
// both ring before a sound, and that ringing would wrap round to the buffer's end (as in
// room_channel.cpp; both have died away well within 100 ms).
constexpr double kMarginS = 0.1;

std::string Text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void Check(bool ok, const std::string& field, const std::string& message) {
  if (!ok) throw RoomOptionError(field, message);
}

// Microphone m's own seed for the parts that differ between microphones (tail, noise).
// std::seed_seq's mixing is fixed by the standard, so this is the same on every library.
std::uint32_t MicSeed(std::uint32_t seed, std::size_t mic) {
  std::seed_seq seq{seed, static_cast<std::uint32_t>(mic), static_cast<std::uint32_t>(kArrayStream)};
  std::uint32_t out = 0;
  seq.generate(&out, &out + 1);
  return out;
}

// Adds an impulse of `amplitude` at `delay` samples (any real number: an exact fractional delay,
// the phase ramp of a band-limited impulse) to the spectrum of an FFT of `size` points.
void AddImpulse(Spectrum& to, double amplitude, double delay, std::size_t size) {
  const double step = -kTwoPi * delay / static_cast<double>(size);
  for (std::size_t k = 0; k < to.size(); ++k) to[k] += std::polar(amplitude, step * static_cast<double>(k));
}

// Delays the signal whose spectrum is `s` by `delay` samples, fractional ones exactly.
void Delay(Spectrum& s, double delay, std::size_t size) {
  const double step = -kTwoPi * delay / static_cast<double>(size);
  for (std::size_t k = 0; k < s.size(); ++k) s[k] *= std::polar(1.0, step * static_cast<double>(k));
}

// The energy of InverseFft(s, size) by Parseval, without the transform. The real transform keeps
// only the real part of DC and of Nyquist (bins its output cannot give a phase).
double Energy(const Spectrum& s, std::size_t size) {
  const std::size_t last = s.size() - 1;
  const bool nyquist = size % 2 == 0;
  double e = s[0].real() * s[0].real();
  for (std::size_t k = 1; k <= last; ++k) {
    e += (k == last && nyquist) ? s[k].real() * s[k].real() : 2.0 * std::norm(s[k]);
  }
  return e / static_cast<double>(size);
}

double Energy(const std::vector<double>& x) {
  double e = 0.0;
  for (double v : x) e += v * v;
  return e;
}

double MeanPower(const std::vector<double>& x) { return x.empty() ? 0.0 : Energy(x) / static_cast<double>(x.size()); }

double PowerForRatio(double signal_power, double ratio_db) { return signal_power * std::pow(10.0, -ratio_db / 10.0); }

double AddAtPower(std::vector<double>& y, const std::vector<double>& d, double power) {
  const double gain = std::sqrt(power / MeanPower(d));
  for (std::size_t i = 0; i < y.size(); ++i) y[i] += gain * d[i];
  return gain;
}

// A far source's signal `x` at each microphone: a plane wave reaches microphone m `advance[m]`
// samples before the origin. x holds `margin` samples either side of the `length` wanted (margin
// at least the largest |advance|), so the circular FFT's wrap never reaches the part kept.
std::vector<std::vector<double>> PlaneWave(const std::vector<double>& x, std::size_t margin, std::size_t length,
                                           const std::vector<double>& advance) {
  const std::size_t size = FftSize(x.size());
  const Spectrum spectrum = ForwardFft(x, size);
  std::vector<std::vector<double>> out;
  for (double a : advance) {
    Spectrum shifted = spectrum;
    Delay(shifted, -a, size);
    const std::vector<double> y = InverseFft(shifted, size);
    out.emplace_back(y.begin() + static_cast<std::ptrdiff_t>(margin),
                     y.begin() + static_cast<std::ptrdiff_t>(margin + length));
  }
  return out;
}

// How much earlier than the origin microphone `p` hears a plane wave from `bearing`, samples.
double Advance(const Microphone2D& p, double bearing, double speed_of_sound, double sample_rate) {
  return (p.x * std::cos(bearing) + p.y * std::sin(bearing)) / speed_of_sound * sample_rate;
}

// Where and how loud everything the room makes arrives at each microphone.
struct Arrivals {
  std::vector<double> direct_s;                   // per microphone, from the output's start
  std::vector<double> direct_gain;                // d / r_m
  std::vector<EarlyReflection> reflections;       // amplitudes scaled to kEarlyShare together
  std::vector<std::vector<double>> reflection_s;  // [microphone][reflection], from the output's start
  double tail_s = 0.0;                            // the tail's time 0: the direct sound at the origin
  std::size_t tail_samples = 0;                   // 0 without a room
  double lead_s = 0.0;
  double last_s = 0.0;                            // the last arrival's end
};

Arrivals PlanArrivals(const RoomOptions& options, const ArraySource& source, const std::vector<double>& reflection_bearing,
                      double sample_rate) {
  Arrivals a;
  const double c = source.speed_of_sound;
  if (options.rt60 > 0.0) {
    RandomSource random(options.seed, kImpulseResponseStream);
    a.reflections = DrawEarlyReflections(options.rt60, random);
    double e = 0.0;
    for (const EarlyReflection& r : a.reflections) e += r.amplitude * r.amplitude;
    for (EarlyReflection& r : a.reflections) r.amplitude *= std::sqrt(kEarlyShare / e);
    a.tail_samples = RoomResponseSamples(options.rt60, sample_rate);
  }
  a.tail_s = source.distance / c;
  const double sx = source.distance * std::cos(source.bearing), sy = source.distance * std::sin(source.bearing);
  double earliest = 0.0;
  a.last_s = a.tail_s + static_cast<double>(a.tail_samples) / sample_rate;
  for (const Microphone2D& p : source.mics) {
    const double r = std::hypot(sx - p.x, sy - p.y);
    a.direct_s.push_back(r / c);
    a.direct_gain.push_back(source.distance / r);
    a.last_s = std::max(a.last_s, r / c);
    std::vector<double> times;
    for (std::size_t k = 0; k < a.reflections.size(); ++k) {
      const double t = a.tail_s + a.reflections[k].delay_s - Advance(p, reflection_bearing[k], c, 1.0);
      times.push_back(t);
      earliest = std::min(earliest, t);
      a.last_s = std::max(a.last_s, t);
    }
    a.reflection_s.push_back(times);
  }
  // Nothing may arrive before the output starts (a far microphone's plane-wave reflection could).
  a.lead_s = -earliest;
  for (double& t : a.direct_s) t += a.lead_s;
  for (auto& times : a.reflection_s) {
    for (double& t : times) t += a.lead_s;
  }
  a.tail_s += a.lead_s;
  a.last_s += a.lead_s;
  return a;
}

// Microphone m's impulse response as a spectrum of `size` points: its direct sound, and the room
// (the reflections at its own delays, its own tail) scaled to the room's DRR at the origin.
Spectrum MicResponse(const Arrivals& a, std::size_t m, const RoomOptions& options, double sample_rate, std::size_t size) {
  Spectrum response(size / 2 + 1);
  AddImpulse(response, a.direct_gain[m], a.direct_s[m] * sample_rate, size);
  if (a.tail_samples == 0) return response;
  Spectrum reverberant(response.size());
  for (std::size_t k = 0; k < a.reflections.size(); ++k) {
    AddImpulse(reverberant, a.reflections[k].amplitude, a.reflection_s[m][k] * sample_rate, size);
  }
  RandomSource random(MicSeed(options.seed, m), kImpulseResponseStream);
  std::vector<double> tail = DiffuseTail(a.tail_samples, options.rt60, sample_rate, random);
  const double tail_gain = std::sqrt((1.0 - kEarlyShare) / Energy(tail));
  for (double& v : tail) v *= tail_gain;
  Spectrum tail_spectrum = ForwardFft(tail, size);
  Delay(tail_spectrum, a.tail_s * sample_rate, size);
  for (std::size_t k = 0; k < reverberant.size(); ++k) reverberant[k] += tail_spectrum[k];
  // The sum to the room's ratio exactly (its cross terms are not quite zero), against the direct
  // energy at the origin, 1.
  const double gain = std::sqrt(std::pow(10.0, -options.drr_db / 10.0) / Energy(reverberant, size));
  for (std::size_t k = 0; k < response.size(); ++k) response[k] += gain * reverberant[k];
  return response;
}

// The mean square of `x` over the samples where `sounding` (of the sent signal) is true, moved
// `shift` samples later: the level definition at a microphone the sound reaches then.
double SoundingPower(const std::vector<double>& x, const std::vector<bool>& sounding, std::size_t shift) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < sounding.size() && i + shift < x.size(); ++i) {
    if (!sounding[i]) continue;
    sum += x[i + shift] * x[i + shift];
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

// Step 4: noise per microphone, and the interferer and the whine as plane waves, each at its
// ratio to each channel's own signal power.
void AddDisturbances(std::vector<std::vector<double>>& channels, const RoomOptions& options, const ArraySource& source,
                     const std::vector<float>& interferer, double sample_rate, ArrayRenderInfo& report) {
  const std::size_t length = channels[0].size();
  if (options.noise != RoomOptions::Noise::kNone) {
    for (std::size_t m = 0; m < channels.size(); ++m) {
      const std::uint32_t seed = MicSeed(options.seed, m);
      const std::vector<double> noise = options.noise == RoomOptions::Noise::kWhite
                                            ? WhiteNoise(length, seed)
                                            : PinkNoise(length, sample_rate, seed);
      const double power = PowerForRatio(report.channels[m].signal_power, options.snr_db);
      AddAtPower(channels[m], noise, power);
      report.channels[m].noise_rms = std::sqrt(power);
    }
  }
  // The plane waves need margin for the largest advance, and a little for the sinc's ringing at
  // their ends.
  double radius = 0.0;
  for (const Microphone2D& p : source.mics) radius = std::max(radius, std::hypot(p.x, p.y));
  const std::size_t margin = static_cast<std::size_t>(std::ceil(radius / source.speed_of_sound * sample_rate)) + 64;
  auto advances = [&](double bearing) {
    std::vector<double> a;
    for (const Microphone2D& p : source.mics) a.push_back(Advance(p, bearing, source.speed_of_sound, sample_rate));
    return a;
  };
  if (!interferer.empty()) {
    std::vector<double> looped(length + 2 * margin);
    for (std::size_t i = 0; i < looped.size(); ++i) looped[i] = interferer[i % interferer.size()];
    if (!(MeanPower(looped) > 0.0)) throw std::invalid_argument("interferer: silent, so it cannot be set to a SIR");
    const auto heard = PlaneWave(looped, margin, length, advances(report.interferer_bearing));
    for (std::size_t m = 0; m < channels.size(); ++m) {
      report.channels[m].interferer_gain =
          AddAtPower(channels[m], heard[m], PowerForRatio(report.channels[m].signal_power, options.sir_db));
    }
  }
  if (options.whine_hz > 0.0) {
    const std::vector<double> whine =
        MotorWhine(length + 2 * margin, sample_rate, options.whine_hz, options.whine_am_hz, options.seed);
    const auto heard = PlaneWave(whine, margin, length, advances(report.whine_bearing));
    for (std::size_t m = 0; m < channels.size(); ++m) {
      const double power = PowerForRatio(report.channels[m].signal_power, options.whine_sir_db);
      AddAtPower(channels[m], heard[m], power);
      report.channels[m].whine_rms = std::sqrt(power);
    }
  }
}

}  // namespace

void ValidateArraySource(const ArraySource& s) {
  Check(!s.mics.empty(), "mics", "no microphones: expected at least one");
  for (std::size_t i = 0; i < s.mics.size(); ++i) {
    const Microphone2D& p = s.mics[i];
    Check(std::isfinite(p.x) && std::isfinite(p.y), "mics",
          "microphone " + std::to_string(i + 1) + " at (" + Text(p.x) + ", " + Text(p.y) + ") m: expected finite coordinates");
    for (std::size_t j = 0; j < i; ++j) {
      Check(!(s.mics[j].x == p.x && s.mics[j].y == p.y), "mics",
            "microphones " + std::to_string(j + 1) + " and " + std::to_string(i + 1) + " both at (" + Text(p.x) + ", " + Text(p.y) +
                ") m: expected distinct positions");
    }
  }
  Check(std::isfinite(s.bearing), "bearing", "bearing " + Text(s.bearing) + " rad: expected a finite angle");
  Check(s.distance > 0.0 && s.distance <= kMaxSourceDistance, "distance",
        "distance " + Text(s.distance) + " m: expected above 0 and at most " + Text(kMaxSourceDistance) + " m");
  Check(s.speed_of_sound > 0.0 && std::isfinite(s.speed_of_sound), "speed_of_sound",
        "speed_of_sound " + Text(s.speed_of_sound) + " m/s: expected above 0");
  const double sx = s.distance * std::cos(s.bearing), sy = s.distance * std::sin(s.bearing);
  for (std::size_t i = 0; i < s.mics.size(); ++i) {
    const double r = std::hypot(sx - s.mics[i].x, sy - s.mics[i].y);
    Check(r >= kMinMicDistance, "distance",
          "distance " + Text(s.distance) + " m: the source is " + Text(r) + " m from microphone " + std::to_string(i + 1) +
              ", expected at least " + Text(kMinMicDistance) + " m");
  }
}

std::vector<std::vector<float>> RenderRoomArray(const std::vector<float>& clean, double sample_rate,
                                                const RoomOptions& options, const ArraySource& source,
                                                const std::vector<float>& interferer, ArrayRenderInfo* info) {
  ValidateRoomOptions(options, sample_rate);
  if (!options.response.empty()) {
    // One measured response is one microphone's; an array's channels each need their own.
    throw RoomOptionError("response", "response: a measured response is one microphone's: expected none for an array");
  }
  ValidateArraySource(source);
  const std::size_t mics = source.mics.size();
  ArrayRenderInfo report;
  report.channels.resize(mics);
  if (clean.empty()) {
    if (info) *info = report;
    return std::vector<std::vector<float>>(mics);
  }

  // The directions of the room's plane waves, all drawn whatever is asked, so that adding an
  // interferer does not move the reflections.
  RandomSource directions(options.seed, kArrayStream);
  std::vector<double> reflection_bearing(kEarlyReflections);
  for (double& b : reflection_bearing) b = kTwoPi * directions.Uniform();
  report.interferer_bearing = kTwoPi * directions.Uniform();
  report.whine_bearing = kTwoPi * directions.Uniform();
  const Arrivals arrivals = PlanArrivals(options, source, reflection_bearing, sample_rate);
  report.lead_s = arrivals.lead_s;

  // 1-2. The source: clock and tilt, once for all microphones.
  const std::vector<float> sent = options.clock_offset == 0.0 ? clean : Resample(clean, 1.0 / (1.0 + options.clock_offset));
  // +2: the last arrival's fractional part, and one sample of its sinc.
  const std::size_t length = sent.size() + static_cast<std::size_t>(std::ceil(arrivals.last_s * sample_rate)) + 2;
  const std::size_t size = FftSize(length + static_cast<std::size_t>(std::ceil(kMarginS * sample_rate)));
  Spectrum spectrum = ForwardFft(std::vector<double>(sent.begin(), sent.end()), size);
  if (options.tilt_db != 0.0) {
    for (std::size_t k = 0; k < spectrum.size(); ++k) {
      spectrum[k] *= std::pow(10.0, TiltGainDb(options, BinHz(k, size, sample_rate)) / 20.0);
    }
  }
  const std::vector<bool> sounding = SoundingSamples(sent, sample_rate);
  report.sounding_fraction = static_cast<double>(std::count(sounding.begin(), sounding.end(), true)) /
                             static_cast<double>(sent.size());

  // 3. Each microphone's signal, and its level.
  std::vector<std::vector<double>> channels(mics);
  for (std::size_t m = 0; m < mics; ++m) {
    Spectrum response = MicResponse(arrivals, m, options, sample_rate, size);
    for (std::size_t k = 0; k < response.size(); ++k) response[k] *= spectrum[k];
    channels[m] = InverseFft(response, size);
    channels[m].resize(length);
    ArrayChannelInfo& channel = report.channels[m];
    channel.direct_delay_s = arrivals.direct_s[m];
    channel.direct_gain = arrivals.direct_gain[m];
    channel.drr_db = options.rt60 > 0.0 ? options.drr_db + 20.0 * std::log10(channel.direct_gain) : HUGE_VAL;
    channel.signal_power =
        SoundingPower(channels[m], sounding, static_cast<std::size_t>(std::lround(channel.direct_delay_s * sample_rate)));
    const bool disturbed = options.noise != RoomOptions::Noise::kNone || !interferer.empty() || options.whine_hz > 0.0;
    if (disturbed && !(channel.signal_power > 0.0)) {
      throw std::invalid_argument("clean signal: silent, so noise, interferer and whine have no level to refer to");
    }
  }

  AddDisturbances(channels, options, source, interferer, sample_rate, report);

  // 5. One gain for all channels: the loudest peak at 0.9 of full scale.
  double peak = 0.0;
  for (const auto& channel : channels) {
    for (double v : channel) peak = std::max(peak, std::fabs(v));
  }
  report.output_gain = peak > 0.0 ? kRoomPeak / peak : 1.0;
  std::vector<std::vector<float>> out(mics, std::vector<float>(length));
  for (std::size_t m = 0; m < mics; ++m) {
    for (std::size_t i = 0; i < length; ++i) out[m][i] = static_cast<float>(report.output_gain * channels[m][i]);
  }
  if (info) *info = report;
  return out;
}

}  // namespace nava_modem
