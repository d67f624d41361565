#include "nava_modem/room_channel.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>

#include <samplerate.h>

#include "nava_modem/measured_like_response.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/noise_sources.h"
#include "nava_modem/real_fft.h"
#include "nava_modem/room_impulse_response.h"
#include "nava_modem/wav_file.h"

namespace nava_modem {
namespace {

std::string Number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void Check(bool ok, const std::string& field, double value, const std::string& unit, const std::string& expected) {
  if (!ok) throw RoomOptionError(field, field + " " + Number(value) + unit + ": expected " + expected);
}

// Within [lo, hi]; false for NaN.
bool Within(double v, double lo, double hi) { return v >= lo && v <= hi; }

double MeanPower(const std::vector<double>& x) {
  if (x.empty()) return 0.0;
  double sum = 0.0;
  for (double v : x) sum += v * v;
  return sum / static_cast<double>(x.size());
}

// Adds `d` to `y` scaled to mean power `power`; returns the gain applied to d.
double AddAtPower(std::vector<double>& y, const std::vector<double>& d, double power) {
  const double gain = std::sqrt(power / MeanPower(d));
  for (std::size_t i = 0; i < y.size(); ++i) y[i] += gain * d[i];
  return gain;
}

double PowerForRatio(double signal_power, double ratio_db) { return signal_power * std::pow(10.0, -ratio_db / 10.0); }

// The zero-phase tilt's ringing before a sound would wrap around the FFT's circle to the end of
// the buffer; this much padding beyond the output keeps it out (the tilt's response, smooth in
// frequency, has died away well within 100 ms).
constexpr double kTiltMarginS = 0.1;

}  // namespace

std::optional<RoomOptions::Model> ParseRoomModel(const std::string& name) {
  if (name == "statistical") return RoomOptions::Model::kStatistical;
  if (name == "measured-like") return RoomOptions::Model::kMeasuredLike;
  if (name == "measured") return RoomOptions::Model::kMeasured;
  return std::nullopt;
}

const char* RoomModelName(RoomOptions::Model model) {
  switch (model) {
    case RoomOptions::Model::kMeasuredLike: return "measured-like";
    case RoomOptions::Model::kMeasured: return "measured";
    case RoomOptions::Model::kStatistical: break;
  }
  return "statistical";
}

void ValidateRoomOptions(const RoomOptions& o, double sample_rate) {
  Check(sample_rate > 0.0 && std::isfinite(sample_rate), "sample_rate", sample_rate, " Hz", "above 0");
  Check(Within(o.rt60, 0.0, 10.0), "rt60", o.rt60, " s", "0 (no reverberation) or above 0 and at most 10");
  Check(Within(o.drr_db, -40.0, 40.0), "drr_db", o.drr_db, " dB", "from -40 to 40");
  Check(o.model == RoomOptions::Model::kStatistical || o.model == RoomOptions::Model::kMeasuredLike ||
            o.model == RoomOptions::Model::kMeasured,
        "model", static_cast<double>(o.model), "", kRoomModelNames);
  Check(o.model != RoomOptions::Model::kMeasured || !o.response.empty(), "model", static_cast<double>(o.model), "",
        "a response given with the measured model (a measured room, moved_rooms.h, is the room)");
  if (o.model == RoomOptions::Model::kMeasuredLike) {
    Check(sample_rate > 2.0 * kResponseBandHighHz, "model", sample_rate, " Hz",
          "a sample rate above " + Number(2.0 * kResponseBandHighHz) + " Hz for a measured-like room (its band)");
  }
  const ResponseGeometry& g = o.geometry;
  const bool placed = g.distance_m != 0.0 || g.source_height_m != 0.0 || g.microphone_height_m != 0.0 || g.ceiling_m != 0.0;
  Check(!placed || o.model == RoomOptions::Model::kMeasuredLike, "geometry", g.distance_m, " m apart",
        "the measured-like model with a geometry (the statistical room has none)");
  if (!o.response.empty()) {
    Check(o.model == RoomOptions::Model::kStatistical || o.model == RoomOptions::Model::kMeasured, "model",
          static_cast<double>(o.model), "",
          "the statistical (the default) or the measured model with a measured response (the response is the room)");
    Check(o.rt60 == 0.0, "rt60", o.rt60, " s", "0 with a measured response (the response is the room)");
    Check(o.drr_db == 0.0, "drr_db", o.drr_db, " dB", "0 with a measured response (the response is the room)");
    const bool finite = std::all_of(o.response.begin(), o.response.end(), [](float v) { return std::isfinite(v); });
    const bool silent = std::all_of(o.response.begin(), o.response.end(), [](float v) { return v == 0.0f; });
    if (!finite || silent) {
      throw RoomOptionError("response", std::string("response: ") + (finite ? "silent" : "not finite") +
                                            ": expected an impulse response with a direct sound");
    }
  }
  Check(Within(o.tilt_db, -40.0, 40.0), "tilt_db", o.tilt_db, " dB", "from -40 to 40");
  Check(o.tilt_low_hz > 0.0 && std::isfinite(o.tilt_low_hz), "tilt_low_hz", o.tilt_low_hz, " Hz", "above 0");
  Check(o.tilt_high_hz > o.tilt_low_hz && std::isfinite(o.tilt_high_hz), "tilt_high_hz", o.tilt_high_hz, " Hz",
        "above tilt_low_hz (" + Number(o.tilt_low_hz) + " Hz)");
  Check(Within(o.clock_offset, -0.05, 0.05), "clock_offset", o.clock_offset, "",
        "from -0.05 to 0.05 (a sound card 5 % slow to 5 % fast)");
  Check(o.noise == RoomOptions::Noise::kNone || o.noise == RoomOptions::Noise::kWhite ||
            o.noise == RoomOptions::Noise::kPink,
        "noise", static_cast<double>(static_cast<int>(o.noise)), "", "none, white or pink");
  Check(Within(o.snr_db, -60.0, 100.0), "snr_db", o.snr_db, " dB", "from -60 to 100");
  Check(Within(o.sir_db, -60.0, 100.0), "sir_db", o.sir_db, " dB", "from -60 to 100");
  Check(Within(o.whine_sir_db, -60.0, 100.0), "whine_sir_db", o.whine_sir_db, " dB", "from -60 to 100");
  const double whine_limit = sample_rate / 2.0 / 1.01;
  Check(o.whine_hz == 0.0 || (o.whine_hz > 0.0 && o.whine_hz < whine_limit), "whine_hz", o.whine_hz, " Hz",
        "0 (none) or above 0 and below " + Number(std::floor(whine_limit)) +
            " Hz (Nyquist less the whine's 1 % wander)");
  Check(Within(o.whine_am_hz, 0.0, 100.0), "whine_am_hz", o.whine_am_hz, " Hz", "from 0 (steady) to 100");
}

double TiltGainDb(const RoomOptions& o, double hz) {
  if (hz <= o.tilt_low_hz) return 0.0;
  if (hz >= o.tilt_high_hz) return o.tilt_db;
  return o.tilt_db * std::log(hz / o.tilt_low_hz) / std::log(o.tilt_high_hz / o.tilt_low_hz);
}

std::vector<bool> SoundingSamples(const std::vector<float>& x, double sample_rate) {
  const std::size_t n = x.size();
  std::vector<bool> sounding(n, false);
  if (n == 0) return sounding;
  // Running sums of squares give each centred window's energy in O(1).
  std::vector<double> cumulative(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cumulative[i + 1] = cumulative[i] + static_cast<double>(x[i]) * x[i];
  const std::size_t half = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(kSoundingWindowS * sample_rate))) / 2;
  std::vector<double> mean_square(n);
  double peak = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t lo = i >= half ? i - half : 0, hi = std::min(n, i + half + 1);
    mean_square[i] = (cumulative[hi] - cumulative[lo]) / static_cast<double>(hi - lo);
    peak = std::max(peak, mean_square[i]);
  }
  if (peak <= 0.0) return sounding;
  const double threshold = kSoundingThreshold * kSoundingThreshold * peak;  // on squares
  for (std::size_t i = 0; i < n; ++i) sounding[i] = mean_square[i] >= threshold;
  return sounding;
}

std::vector<float> Resample(const std::vector<float>& in, double ratio) {
  if (!(ratio >= 1.0 / 256.0 && ratio <= 256.0)) {
    throw std::invalid_argument("resampling ratio " + Number(ratio) + ": expected from 1/256 to 256");
  }
  if (in.empty()) return {};
  std::vector<float> out(static_cast<std::size_t>(std::ceil(static_cast<double>(in.size()) * ratio)) + 16);
  SRC_DATA data{};
  data.data_in = in.data();
  data.input_frames = static_cast<long>(in.size());
  data.data_out = out.data();
  data.output_frames = static_cast<long>(out.size());
  data.src_ratio = ratio;
  const int error = src_simple(&data, SRC_SINC_BEST_QUALITY, 1);
  if (error != 0) throw std::runtime_error(std::string("libsamplerate: ") + src_strerror(error));
  out.resize(static_cast<std::size_t>(data.output_frames_gen));
  return out;
}

std::vector<float> ReadAudioAt(const std::string& path, double rate) {
  const Audio audio = ReadAudioFile(path);
  return Resample(audio.samples, rate / audio.sample_rate);
}

std::vector<float> RenderRoom(const std::vector<float>& clean, double sample_rate, const RoomOptions& options,
                              const std::vector<float>& interferer, RoomRenderInfo* info) {
  ValidateRoomOptions(options, sample_rate);
  RoomRenderInfo report;
  if (clean.empty()) {
    if (info) *info = report;
    return {};
  }

  // 1. The sender's clock: its samples are played at (1 + offset) x the rate they were made for.
  const std::vector<float> sent = options.clock_offset == 0.0 ? clean : Resample(clean, 1.0 / (1.0 + options.clock_offset));

  // 2-3. Tilt and room in one spectrum.
  const bool given = !options.response.empty();
  const bool like = !given && options.model == RoomOptions::Model::kMeasuredLike && options.rt60 > 0.0;
  const std::vector<float>& response =
      given ? options.response
            : like ? MeasuredLikeResponse(options.rt60, options.drr_db, sample_rate, options.seed, options.geometry)
                   : RoomImpulseResponse(options.rt60, options.drr_db, sample_rate, options.seed);
  // Where the packet is heard: a measured (or measured-like) response's delay to its largest
  // peak (0 for the statistical one).
  std::size_t delay = 0;
  if (given || like) {
    report.measured_drr_db = sample_rate > 2.0 * kResponseBandHighHz ? MeasureResponse(response, sample_rate).drr_db
                                                                      : MeasureDrrDb(response);
    for (std::size_t k = 0; k < response.size(); ++k) {
      if (std::fabs(response[k]) > std::fabs(response[delay])) delay = k;
    }
  } else {
    report.measured_drr_db = MeasureDrrDb(response);
  }
  const std::size_t length = sent.size() + response.size() - 1;
  const std::size_t size = FftSize(length + static_cast<std::size_t>(std::ceil(kTiltMarginS * sample_rate)));
  std::vector<std::complex<double>> spectrum = ForwardFft(std::vector<double>(sent.begin(), sent.end()), size);
  if (response.size() > 1) {
    const std::vector<std::complex<double>> room =
        ForwardFft(std::vector<double>(response.begin(), response.end()), size);
    for (std::size_t k = 0; k < spectrum.size(); ++k) spectrum[k] *= room[k];
  }
  if (options.tilt_db != 0.0) {
    for (std::size_t k = 0; k < spectrum.size(); ++k) {
      spectrum[k] *= std::pow(10.0, TiltGainDb(options, BinHz(k, size, sample_rate)) / 20.0);
    }
  }
  std::vector<double> mic = InverseFft(spectrum, size);
  mic.resize(length);

  // The level every ratio refers to.
  const std::vector<bool> sounding = SoundingSamples(sent, sample_rate);
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    if (!sounding[i]) continue;
    sum += mic[i + delay] * mic[i + delay];
    ++count;
  }
  report.signal_power = count ? sum / static_cast<double>(count) : 0.0;
  report.sounding_fraction = static_cast<double>(count) / static_cast<double>(sent.size());
  const bool disturbed = options.noise != RoomOptions::Noise::kNone || !interferer.empty() || options.whine_hz > 0.0;
  if (disturbed && !(report.signal_power > 0.0)) {
    throw std::invalid_argument("clean signal: silent, so noise, interferer and whine have no level to refer to");
  }

  // 4. The disturbances at their ratios.
  if (options.noise != RoomOptions::Noise::kNone) {
    const std::vector<double> noise = options.noise == RoomOptions::Noise::kWhite
                                          ? WhiteNoise(length, options.seed)
                                          : PinkNoise(length, sample_rate, options.seed);
    const double power = PowerForRatio(report.signal_power, options.snr_db);
    AddAtPower(mic, noise, power);
    report.noise_rms = std::sqrt(power);
  }
  if (!interferer.empty()) {
    std::vector<double> looped(length);
    for (std::size_t i = 0; i < length; ++i) looped[i] = interferer[i % interferer.size()];
    if (!(MeanPower(looped) > 0.0)) throw std::invalid_argument("interferer: silent, so it cannot be set to a SIR");
    report.interferer_gain = AddAtPower(mic, looped, PowerForRatio(report.signal_power, options.sir_db));
  }
  if (options.whine_hz > 0.0) {
    const std::vector<double> whine = MotorWhine(length, sample_rate, options.whine_hz, options.whine_am_hz, options.seed);
    const double power = PowerForRatio(report.signal_power, options.whine_sir_db);
    AddAtPower(mic, whine, power);
    report.whine_rms = std::sqrt(power);
  }

  // 5. Peak at 0.9 of full scale.
  double peak = 0.0;
  for (double v : mic) peak = std::max(peak, std::fabs(v));
  report.output_gain = peak > 0.0 ? kRoomPeak / peak : 1.0;
  std::vector<float> out(length);
  for (std::size_t i = 0; i < length; ++i) out[i] = static_cast<float>(report.output_gain * mic[i]);
  if (info) *info = report;
  return out;
}

}  // namespace nava_modem
