#include "nava_modem/measured_response.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "nava_modem/biquad.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"

namespace nava_modem {
namespace {

// The response in [lo, hi] Hz: 4th-order Butterworth high- and low-pass, run forwards and
// backwards (zero phase, so the direct sound stays where it was). The figures of
// ../shared/realrooms/README.md come out to within 0.05 dB this way; a brick-wall FFT band, which
// this replaced, read up to 0.6 dB higher where the direct sound is strong.
std::vector<double> BandPass(const std::vector<float>& x, double sample_rate, double lo, double hi) {
  std::vector<Biquad> sections = Butterworth(sample_rate, lo, true, 4);
  const std::vector<Biquad> low_pass = Butterworth(sample_rate, hi, false, 4);
  sections.insert(sections.end(), low_pass.begin(), low_pass.end());
  return FilterForwardBackward(std::vector<double>(x.begin(), x.end()), sections);
}

// The decay time from Schroeder's curve (dB, from 0 at the start) between -from and -to dB:
// the least-squares line's slope extended to 60 dB; NaN when the curve does not reach -to dB.
double DecayTime(const std::vector<double>& curve_db, double sample_rate, double from, double to) {
  std::size_t first = curve_db.size(), last = curve_db.size();
  for (std::size_t k = 0; k < curve_db.size(); ++k) {
    if (first == curve_db.size() && curve_db[k] <= -from) first = k;
    if (curve_db[k] <= -to) {
      last = k;
      break;
    }
  }
  if (last == curve_db.size() || last <= first + 1) return std::numeric_limits<double>::quiet_NaN();
  double st = 0.0, sy = 0.0, stt = 0.0, sty = 0.0;
  const double n = static_cast<double>(last - first + 1);
  for (std::size_t k = first; k <= last; ++k) {
    const double t = static_cast<double>(k) / sample_rate;
    st += t, sy += curve_db[k], stt += t * t, sty += t * curve_db[k];
  }
  const double slope = (n * sty - st * sy) / (n * stt - st * st);  // dB per second, negative
  return slope < 0.0 ? -60.0 / slope : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::vector<float> LoadImpulseResponse(const std::string& path, std::optional<int> channel, double sample_rate) {
  if (!(sample_rate > 0.0 && std::isfinite(sample_rate))) {
    throw std::invalid_argument("sample rate " + std::to_string(sample_rate) + " Hz: expected above 0");
  }
  MultiAudio audio;
  try {
    audio = ReadAudioChannels(path);
  } catch (const std::exception& e) {
    throw ResponseFileError(std::string(e.what()) + ": expected an impulse response as an audio file");
  }
  const int channels = static_cast<int>(audio.channels.size());
  if (!channel && channels > 1) {
    throw ResponseFileError(path + ": " + std::to_string(channels) +
                            " channels: expected one, or a channel chosen (--channel 0.." + std::to_string(channels - 1) + ")");
  }
  const int c = channel.value_or(0);
  if (c < 0 || c >= channels) {
    throw ResponseFileError(path + ": channel " + std::to_string(c) + " asked for: expected 0.." +
                            std::to_string(channels - 1) + " (the file has " + std::to_string(channels) + ")");
  }
  std::vector<float> response = audio.channels[static_cast<std::size_t>(c)];
  const bool silent = std::all_of(response.begin(), response.end(), [](float v) { return v == 0.0f || !std::isfinite(v); });
  if (response.empty() || silent) {
    throw ResponseFileError(path + (channel ? ", channel " + std::to_string(c) : std::string()) +
                            ": silent: expected an impulse response with a direct sound");
  }
  if (audio.sample_rate != sample_rate) response = Resample(response, sample_rate / audio.sample_rate);
  return response;
}

ResponseMeasures MeasureResponse(const std::vector<float>& response, double sample_rate) {
  if (!(sample_rate > 2.0 * kResponseBandHighHz)) {
    throw std::invalid_argument("sample rate " + std::to_string(sample_rate) + " Hz: expected above " +
                                std::to_string(2.0 * kResponseBandHighHz) + " to measure in the modems' band");
  }
  if (response.empty()) throw std::invalid_argument("impulse response: empty");
  const std::vector<double> band = BandPass(response, sample_rate, kResponseBandLowHz, kResponseBandHighHz);
  ResponseMeasures m;
  double largest = 0.0;
  for (std::size_t k = 0; k < band.size(); ++k) {
    if (std::abs(band[k]) > largest) largest = std::abs(band[k]), m.peak = k;
  }
  if (!(largest > 0.0)) throw std::invalid_argument("impulse response: silent in 600-5400 Hz");
  const std::size_t half = static_cast<std::size_t>(std::lround(kDirectHalfWidthS * sample_rate));
  const std::size_t direct_end = std::min(band.size(), m.peak + half + 1);
  const std::size_t direct_start = m.peak >= half ? m.peak - half : 0;
  double before = 0.0, direct = 0.0, after = 0.0;
  for (std::size_t k = 0; k < direct_start; ++k) before += band[k] * band[k];
  for (std::size_t k = direct_start; k < direct_end; ++k) direct += band[k] * band[k];
  for (std::size_t k = direct_end; k < band.size(); ++k) after += band[k] * band[k];
  m.drr_db = after > 0.0 ? 10.0 * std::log10(direct / after) : std::numeric_limits<double>::infinity();
  m.before_db = before > 0.0 ? 10.0 * std::log10(before / direct) : -std::numeric_limits<double>::infinity();
  m.after_s = static_cast<double>(band.size() - direct_end) / sample_rate;
  // Schroeder's backward integral from the direct sound on.
  std::vector<double> curve(band.size() - m.peak);
  double sum = 0.0;
  for (std::size_t k = band.size(); k-- > m.peak;) {
    sum += band[k] * band[k];
    curve[k - m.peak] = sum;
  }
  const double total = curve[0];
  for (double& v : curve) v = 10.0 * std::log10(v / total + 1e-300);
  m.rt60_s = DecayTime(curve, sample_rate, 5.0, 35.0);
  if (!std::isfinite(m.rt60_s)) m.rt60_s = DecayTime(curve, sample_rate, 5.0, 25.0);
  return m;
}

std::optional<std::string> ResponseProblem(const ResponseMeasures& m) {
  char text[200];
  if (m.after_s < kMinTailS) {
    std::snprintf(text, sizeof text, "too short: %.1f ms after its direct sound, expected at least %.0f ms",
                  m.after_s * 1e3, kMinTailS * 1e3);
    return std::string(text);
  }
  if (m.before_db >= kMaxBeforeDb) {
    std::snprintf(text, sizeof text,
                  "no direct peak: %.1f dB more sound before its loudest peak than within it, expected under %.0f "
                  "(a room's response starts near its direct sound)", m.before_db, kMaxBeforeDb);
    return std::string(text);
  }
  if (!std::isfinite(m.rt60_s)) return std::string("its decay does not fall 25 dB in 600-5400 Hz: no RT60 to read");
  return std::nullopt;
}

}  // namespace nava_modem
