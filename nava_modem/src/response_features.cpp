#include "nava_modem/response_features.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>

#include "nava_modem/math_constants.h"
#include "nava_modem/real_fft.h"

namespace nava_modem {
namespace {

constexpr double kToneHalfWidthHz = 150.0;
constexpr double kEnvelopeS = 0.0005;

double Db(double ratio) { return ratio > 0.0 ? 10.0 * std::log10(ratio) : -std::numeric_limits<double>::infinity(); }

// Energy per bin of `x`'s spectrum between lo and hi Hz (mean over the bins; 0 with none).
double MeanPower(const std::vector<std::complex<double>>& spectrum, std::size_t n, double sample_rate, double lo,
                 double hi) {
  double sum = 0.0;
  int bins = 0;
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    const double hz = BinHz(k, n, sample_rate);
    if (hz < lo || hz > hi) continue;
    sum += std::norm(spectrum[k]);
    ++bins;
  }
  return bins > 0 ? sum / bins : 0.0;
}

// The third-octave levels of a spectrum, relative to their mean, and their standard deviation.
double ColourOf(const std::vector<std::complex<double>>& spectrum, std::size_t n, double sample_rate,
                double (&levels)[kColourBands]) {
  double mean = 0.0;
  for (int k = 0; k < kColourBands; ++k) {
    const double centre = ColourBandHz(k), edge = std::pow(2.0, 1.0 / 6.0);
    levels[k] = Db(std::max(MeanPower(spectrum, n, sample_rate, centre / edge, centre * edge), 1e-300));
    mean += levels[k] / kColourBands;
  }
  double spread = 0.0;
  for (double& level : levels) {
    level -= mean;
    spread += level * level / kColourBands;
  }
  return std::sqrt(spread);
}

// Schroeder's backward integral of `band` from `from` on, in dB under its start; empty when
// nothing is there.
std::vector<double> SchroederDb(const std::vector<double>& band, std::size_t from) {
  std::vector<double> curve(band.size() - std::min(from, band.size()));
  double sum = 0.0;
  for (std::size_t k = band.size(); k-- > from;) {
    sum += band[k] * band[k];
    curve[k - from] = sum;
  }
  if (!(sum > 0.0)) return {};
  for (double& v : curve) v = Db(std::max(v / sum, 1e-300));
  return curve;
}

// The RT60 of `response` in [lo, hi] Hz from its Schroeder curve after `peak` (T30, else T20).
double OctaveRt60(const std::vector<float>& response, double sample_rate, std::size_t peak, double lo, double hi) {
  const std::vector<double> curve = SchroederDb(ResponseBand(response, sample_rate, lo, hi), peak);
  if (curve.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double t30 = DecayTime(curve, sample_rate, 5.0, 35.0);
  return std::isfinite(t30) ? t30 : DecayTime(curve, sample_rate, 5.0, 25.0);
}

// The early decay time (0 to -10 dB of Schroeder's curve, extended to 60 dB) of `band` from
// `from` on; NaN when nothing is there.
double ReverbEarlyDecay(const std::vector<double>& band, std::size_t from, double sample_rate) {
  const std::vector<double> curve = SchroederDb(band, from);
  return curve.empty() ? std::numeric_limits<double>::quiet_NaN() : DecayTime(curve, sample_rate, 0.0, 10.0);
}

}  // namespace

double ColourBandHz(int k) { return 630.0 * std::pow(2.0, k / 3.0); }

ResponseFeatures MeasureFeatures(const std::vector<float>& response, double sample_rate, double tone_a_hz,
                                 double tone_b_hz) {
  ResponseFeatures f;
  f.measures = MeasureResponse(response, sample_rate);
  for (double tone : {tone_a_hz, tone_b_hz}) {
    if (!(tone > kToneHalfWidthHz && tone + kToneHalfWidthHz < sample_rate / 2.0)) {
      throw std::invalid_argument("tone " + std::to_string(tone) + " Hz: expected its +-" +
                                  std::to_string(kToneHalfWidthHz) + " Hz between 0 and half of " +
                                  std::to_string(sample_rate) + " Hz");
    }
  }
  const auto samples = [&](double s) { return static_cast<std::size_t>(std::lround(s * sample_rate)); };
  // With silence before it, as the figures are read.
  const std::vector<float> led = WithLead(response, sample_rate);
  const std::vector<double> band = ResponseBand(led, sample_rate, kResponseBandLowHz, kResponseBandHighHz);
  const std::size_t n = band.size(), peak = f.measures.peak + MeasureLeadSamples(sample_rate);
  const std::size_t half = samples(kDirectHalfWidthS);
  const std::size_t direct_begin = peak >= half ? peak - half : 0, direct_end = std::min(n, peak + half + 1);
  const std::size_t early_end = std::min(n, peak + samples(kEarlyEndS) + 1);

  double direct = 0.0, moment = 0.0, early = 0.0;
  for (std::size_t k = direct_begin; k < direct_end; ++k) {
    const double t = (static_cast<double>(k) - static_cast<double>(peak)) / sample_rate;
    direct += band[k] * band[k];
    moment += t * t * band[k] * band[k];
  }
  for (std::size_t k = direct_end; k < early_end; ++k) early += band[k] * band[k];
  f.direct_spread_ms = direct > 0.0 ? 1e3 * std::sqrt(moment / direct) : 0.0;
  f.early_db = Db(early / direct);
  const std::size_t onset_end = std::min(n, peak + samples(kOnsetEndS) + 1);
  double onset = 0.0, reverberant = 0.0;
  for (std::size_t k = direct_end; k < n; ++k) {
    reverberant += band[k] * band[k];
    if (k < onset_end) onset += band[k] * band[k];
  }
  f.onset_db = Db(onset / reverberant);
  f.reverb_edt_ratio = ReverbEarlyDecay(band, direct_end, sample_rate) / f.measures.rt60_s;

  // The energy envelope over kEnvelopeS about each sample (a running sum).
  const std::size_t reach = std::max<std::size_t>(1, samples(kEnvelopeS / 2.0));
  const auto envelope = [&](std::size_t k) {
    double e = 0.0;
    for (std::size_t j = k >= reach ? k - reach : 0; j <= std::min(n - 1, k + reach); ++j) e += band[j] * band[j];
    return e;
  };
  const double at_peak = envelope(peak);
  double strongest = 0.0;
  std::size_t strongest_at = direct_end;
  for (std::size_t k = direct_end; k < early_end; k += std::max<std::size_t>(1, reach / 2)) {
    const double e = envelope(k);
    if (e > strongest) strongest = e, strongest_at = k;
  }
  f.strongest_early_ms = 1e3 * static_cast<double>(strongest_at - peak) / sample_rate;
  f.strongest_early_db = Db(strongest / at_peak);

  // The colouring: the whole response from its direct sound on; the direct sound alone through
  // a Hann window, zero-padded to a fine grid of bins.
  const std::vector<double> from_direct(led.begin() + static_cast<std::ptrdiff_t>(direct_begin), led.end());
  const std::size_t whole = FftSize(from_direct.size());
  const std::vector<std::complex<double>> spectrum = ForwardFft(from_direct, whole);
  f.colour_db = ColourOf(spectrum, whole, sample_rate, f.band_db);
  std::vector<double> windowed(direct_end - direct_begin);
  for (std::size_t k = 0; k < windowed.size(); ++k) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * kPi * (static_cast<double>(k) + 0.5) / static_cast<double>(windowed.size()));
    windowed[k] = w * led[direct_begin + k];
  }
  const std::size_t fine = FftSize(std::max<std::size_t>(windowed.size(), samples(0.1)));
  f.direct_colour_db = ColourOf(ForwardFft(windowed, fine), fine, sample_rate, f.direct_band_db);
  f.tone_ratio_db = Db(MeanPower(spectrum, whole, sample_rate, tone_a_hz - kToneHalfWidthHz, tone_a_hz + kToneHalfWidthHz) /
                       MeanPower(spectrum, whole, sample_rate, tone_b_hz - kToneHalfWidthHz, tone_b_hz + kToneHalfWidthHz));

  const double low = OctaveRt60(led, sample_rate, peak, 1000.0 / std::sqrt(2.0), 1000.0 * std::sqrt(2.0));
  const double high = OctaveRt60(led, sample_rate, peak, 4000.0 / std::sqrt(2.0), kResponseBandHighHz);
  f.decay_ratio = high / low;
  return f;
}

}  // namespace nava_modem
