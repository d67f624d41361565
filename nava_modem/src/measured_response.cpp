#include "nava_modem/measured_response.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "nava_modem/biquad.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"

namespace nava_modem {

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

namespace {

void CheckMeasurable(const std::vector<float>& response, double sample_rate) {
  if (!(sample_rate > 2.0 * kResponseBandHighHz)) {
    throw std::invalid_argument("sample rate " + std::to_string(sample_rate) + " Hz: expected above " +
                                std::to_string(2.0 * kResponseBandHighHz) + " to measure in the modems' band");
  }
  if (response.empty()) throw std::invalid_argument("impulse response: empty");
}

std::size_t LargestPeak(const std::vector<double>& band) {
  std::size_t peak = 0;
  double largest = 0.0;
  for (std::size_t k = 0; k < band.size(); ++k) {
    if (std::abs(band[k]) > largest) largest = std::abs(band[k]), peak = k;
  }
  if (!(largest > 0.0)) throw std::invalid_argument("impulse response: silent in 600-5400 Hz");
  return peak;
}

// Where the response's figures stop: the samples before `end` count, each less `floor` (the
// noise's energy per sample), and `tail` (energy) is taken to lie beyond.
struct Cut {
  std::size_t end;
  double floor;
  double tail;
  double slope = 0.0;  // dB per second the tail decays at (below 0), 0 without a tail
};

// The decay and its cut (see MeasureResponseOverNoise) for a band-passed response over a noise
// floor of `floor` per sample.
Cut CutAtFloor(const std::vector<double>& band, double sample_rate, double floor) {
  const std::size_t peak = LargestPeak(band);
  const std::size_t half = static_cast<std::size_t>(std::lround(kDirectHalfWidthS * sample_rate));
  const std::size_t first = std::min(band.size(), peak + half + 1);
  if (!(floor > 0.0)) return Cut{band.size(), 0.0, 0.0};
  // 10 ms energies after the direct sound, in dB.
  const std::size_t block = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.010 * sample_rate)));
  std::vector<double> level, time;
  for (std::size_t b = first; b + block <= band.size(); b += block) {
    double e = 0.0;
    for (std::size_t k = b; k < b + block; ++k) e += band[k] * band[k];
    level.push_back(10.0 * std::log10(std::max(e / static_cast<double>(block), 1e-300)));
    time.push_back((static_cast<double>(b - peak) + 0.5 * static_cast<double>(block)) / sample_rate);
  }
  // Fitted from where Schroeder's curve (over the energies less the floor) has fallen 5 dB, past
  // the early reflections as T30 starts, to the end, noise blocks and all: they pin the knee
  // where the decay sinks into the floor, which a line fitted above the floor alone cannot place
  // when the decay stands only 20 to 30 dB above it.
  std::vector<double> remaining(level.size() + 1, 0.0);
  for (std::size_t j = level.size(); j-- > 0;) remaining[j] = remaining[j + 1] + std::pow(10.0, level[j] / 10.0) - floor;
  std::size_t from = 0;
  while (from < level.size() && remaining[from] > remaining[0] * std::pow(10.0, -0.5)) ++from;
  if (level.size() < from + 5) return Cut{band.size(), floor, 0.0};
  const double floor_db = 10.0 * std::log10(floor);
  {
    // A decay that stands higher than kLateFitDb above the floor is fitted over its last
    // kLateFitDb only (judged on the means of 5 blocks), as Lundeby fits the late decay: a room's
    // decay often slows as it goes on (the measured basement's reads RT60 3.9 s over its first
    // 10 dB and 5.5 to 6.4 s over the next), and it is the late slope the curve follows below
    // the floor.
    std::size_t late = from;
    const auto mean_db = [&](std::size_t j) {
      double e = 0.0;
      const std::size_t stop = std::min(level.size(), j + 5);
      for (std::size_t i = j; i < stop; ++i) e += std::pow(10.0, level[i] / 10.0);
      return 10.0 * std::log10(e / static_cast<double>(stop - j));
    };
    while (late + 5 < level.size() && mean_db(late) > floor_db + kLateFitDb) ++late;
    if (late + 5 < level.size() && late > from) from = late;
  }
  const double top = *std::max_element(level.begin() + static_cast<std::ptrdiff_t>(from), level.end());
  if (top < floor_db + kFloorMarginDb) return Cut{first, floor, 0.0};  // no decay to speak of
  // The model: level(t) = 10 log10(a 10^(slope t / 10) + floor), least squares in dB, searched
  // on a coarse grid of RT60 (0.05 to 60 s, 3 % apart) and of a (1 dB apart, within 15 dB of
  // passing through the top of the fitted range), then on a fine one around the best (0.3 %,
  // 0.05 dB).
  double best_cost = std::numeric_limits<double>::infinity(), best_rt60 = 1.0, best_a_db = 0.0;
  const auto search = [&](double rt60_lo, double rt60_hi, double rt60_step, double a_lo, double a_hi, double a_step,
                          bool around_top) {
    for (double rt60 = rt60_lo; rt60 <= rt60_hi; rt60 *= rt60_step) {
      const double slope = -60.0 / rt60;
      const double centre = around_top ? top - slope * time[from] : 0.0;
      for (double a_db = centre + a_lo; a_db <= centre + a_hi; a_db += a_step) {
        double cost = 0.0;
        for (std::size_t j = from; j < level.size() && cost < best_cost; ++j) {
          const double model = 10.0 * std::log10(std::pow(10.0, (a_db + slope * time[j]) / 10.0) + floor);
          cost += (model - level[j]) * (model - level[j]);
        }
        if (cost < best_cost) best_cost = cost, best_rt60 = rt60, best_a_db = a_db;
      }
    }
  };
  search(0.05, 60.0, 1.03, -15.0, 15.0, 1.0, true);
  const double coarse_rt60 = best_rt60, coarse_a_db = best_a_db;
  search(coarse_rt60 / 1.04, coarse_rt60 * 1.04, 1.003, coarse_a_db - 1.5, coarse_a_db + 1.5, 0.05, false);
  const double best_slope = -60.0 / best_rt60;

  // Cut where the decay meets the floor; beyond, the model's decay.
  const double meet_s = (floor_db - best_a_db) / best_slope;
  const double end = std::clamp(static_cast<double>(peak) + meet_s * sample_rate, static_cast<double>(first),
                                static_cast<double>(band.size()));
  const double end_s = (end - static_cast<double>(peak)) / sample_rate;
  const double at_end = std::pow(10.0, (best_a_db + best_slope * end_s) / 10.0);
  const double tail = at_end * sample_rate * 10.0 / (-best_slope * std::log(10.0));
  return Cut{static_cast<std::size_t>(end), floor, tail, best_slope};
}

// The figures of a band-passed response up to `cut`; `lead`: the silence put before it, which
// holds no sound from before the direct one and is taken off the peak's sample.
ResponseMeasures Figures(const std::vector<double>& band, double sample_rate, const Cut& cut, std::size_t lead) {
  ResponseMeasures m;
  m.peak = LargestPeak(band);
  const std::size_t half = static_cast<std::size_t>(std::lround(kDirectHalfWidthS * sample_rate));
  const std::size_t end = std::max(std::min(cut.end, band.size()), std::min(band.size(), m.peak + 1));
  const std::size_t direct_end = std::min(end, m.peak + half + 1);
  const std::size_t direct_start = m.peak >= half ? m.peak - half : 0;
  const auto energy = [&](std::size_t k) { return band[k] * band[k] - cut.floor; };
  double before = 0.0, direct = 0.0, after = cut.tail;
  for (std::size_t k = std::min(lead, direct_start); k < direct_start; ++k) before += energy(k);
  for (std::size_t k = direct_start; k < direct_end; ++k) direct += energy(k);
  for (std::size_t k = direct_end; k < end; ++k) after += energy(k);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Over a noise floor either can come out at or below 0: no direct sound left, or no reverberation.
  if (!(direct > 0.0)) direct = 1e-300;
  m.drr_db = after > 0.0 ? 10.0 * std::log10(direct / after) : kInf;
  m.before_db = before > 0.0 ? 10.0 * std::log10(before / direct) : -kInf;
  m.after_s = static_cast<double>(end - direct_end) / sample_rate;
  // Schroeder's backward integral from the direct sound on.
  std::vector<double> curve(end - m.peak);
  double sum = cut.tail;
  for (std::size_t k = end; k-- > m.peak;) {
    sum += energy(k);
    curve[k - m.peak] = sum;
  }
  const double total = curve[0];
  for (double& v : curve) v = 10.0 * std::log10(std::max(v / total, 1e-300));
  // Beyond a cut the curve follows the tail's line, down to where the decay times are read.
  if (cut.tail > 0.0 && cut.slope < 0.0 && !curve.empty()) {
    const double at_cut = 10.0 * std::log10(cut.tail / total);
    for (std::size_t j = 1; at_cut + cut.slope * static_cast<double>(j) / sample_rate > -40.0; ++j) {
      curve.push_back(at_cut + cut.slope * static_cast<double>(j) / sample_rate);
    }
  }
  m.rt60_s = DecayTime(curve, sample_rate, 5.0, 35.0);
  if (!std::isfinite(m.rt60_s)) m.rt60_s = DecayTime(curve, sample_rate, 5.0, 25.0);
  m.peak = m.peak >= lead ? m.peak - lead : 0;
  return m;
}

}  // namespace

std::vector<double> ResponseBand(const std::vector<float>& x, double sample_rate, double lo, double hi) {
  // Zero phase, so the direct sound stays where it was. The figures of ../shared/realrooms/README.md
  // come out to within 0.05 dB this way; a brick-wall FFT band, which this replaced, read up to
  // 0.6 dB higher where the direct sound is strong.
  std::vector<Biquad> sections = Butterworth(sample_rate, lo, true, 4);
  const std::vector<Biquad> low_pass = Butterworth(sample_rate, hi, false, 4);
  sections.insert(sections.end(), low_pass.begin(), low_pass.end());
  return FilterForwardBackward(std::vector<double>(x.begin(), x.end()), sections);
}

std::size_t MeasureLeadSamples(double sample_rate) {
  return static_cast<std::size_t>(std::lround(kMeasureLeadS * sample_rate));
}

std::vector<float> WithLead(const std::vector<float>& response, double sample_rate) {
  std::vector<float> led(MeasureLeadSamples(sample_rate), 0.0f);
  led.insert(led.end(), response.begin(), response.end());
  return led;
}

std::vector<double> LeadBand(const std::vector<float>& response, double sample_rate) {
  return ResponseBand(WithLead(response, sample_rate), sample_rate, kResponseBandLowHz, kResponseBandHighHz);
}

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
  CheckMeasurable(response, sample_rate);
  const std::vector<double> band = LeadBand(response, sample_rate);
  return Figures(band, sample_rate, Cut{band.size(), 0.0, 0.0}, MeasureLeadSamples(sample_rate));
}

ResponseMeasures MeasureResponseOverNoise(const std::vector<float>& response, double noise_power, double sample_rate) {
  CheckMeasurable(response, sample_rate);
  if (!(noise_power >= 0.0 && std::isfinite(noise_power))) {
    throw std::invalid_argument("impulse response's noise power " + std::to_string(noise_power) + ": expected 0 or above");
  }
  const std::vector<double> band = LeadBand(response, sample_rate);
  return Figures(band, sample_rate, CutAtFloor(band, sample_rate, noise_power), MeasureLeadSamples(sample_rate));
}

double InBandPower(const std::vector<float>& x, double sample_rate) {
  if (x.empty()) return 0.0;
  double sum = 0.0;
  for (double v : ResponseBand(x, sample_rate, kResponseBandLowHz, kResponseBandHighHz)) sum += v * v;
  return sum / static_cast<double>(x.size());
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

std::vector<float> DrierResponse(const std::vector<float>& response, double sample_rate, double drr_db) {
  const ResponseMeasures own = MeasureResponse(response, sample_rate);
  if (!std::isfinite(drr_db) || drr_db < own.drr_db) {
    throw std::invalid_argument("drier response: expected a DRR of at least the response's own " +
                                std::to_string(own.drr_db) + " dB, got " + std::to_string(drr_db));
  }
  const std::size_t from = own.peak + static_cast<std::size_t>(std::lround(kDirectHalfWidthS * sample_rate));
  auto scaled = [&](double gain) {
    std::vector<float> out = response;
    for (std::size_t k = from; k < out.size(); ++k) out[k] = static_cast<float>(gain * out[k]);
    return out;
  };
  // The DRR falls as the gain rises (the band's filters spread a little of the direct sound past
  // `from`, so it is not exactly -20 log10(gain) away): bisection on the gain's logarithm.
  double low = -8.0, high = 0.0;  // log10 of the gain
  for (int k = 0; k < 60 && high - low > 1e-6; ++k) {
    const double mid = 0.5 * (low + high);
    if (MeasureResponse(scaled(std::pow(10.0, mid)), sample_rate).drr_db > drr_db) {
      low = mid;
    } else {
      high = mid;
    }
  }
  std::vector<float> out = scaled(std::pow(10.0, 0.5 * (low + high)));
  // A response whose direct sound alone (its filters' spread past `from`) reads below the target
  // cannot be made that dry by scaling what follows.
  const double reached = MeasureResponse(out, sample_rate).drr_db;
  if (!(std::abs(reached - drr_db) <= kDrierToleranceDb)) {
    throw std::invalid_argument("drier response: a DRR of " + std::to_string(drr_db) +
                                " dB is out of reach by scaling the reverberation (" + std::to_string(reached) +
                                " dB with none of it left)");
  }
  return out;
}

}  // namespace nava_modem
