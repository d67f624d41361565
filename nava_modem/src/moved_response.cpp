#include "nava_modem/moved_response.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "nava_modem/measured_response.h"

namespace nava_modem {
namespace {

// Where the reverberation starts: just past the direct sound's window.
std::size_t ReverberationStart(std::size_t peak, std::size_t size, double sample_rate) {
  return std::min(size, peak + static_cast<std::size_t>(std::lround(kDirectHalfWidthS * sample_rate)) + 1);
}

// The in-band energies of `response` before `from` and from there on.
std::pair<double, double> SplitEnergies(const std::vector<float>& response, std::size_t from, double sample_rate) {
  std::vector<float> head(response.begin(), response.begin() + static_cast<std::ptrdiff_t>(from));
  head.resize(response.size(), 0.0f);
  std::vector<float> rest(response.size(), 0.0f);
  std::copy(response.begin() + static_cast<std::ptrdiff_t>(from), response.end(), rest.begin() + static_cast<std::ptrdiff_t>(from));
  return {InBandPower(WithLead(head, sample_rate), sample_rate), InBandPower(WithLead(rest, sample_rate), sample_rate)};
}

// `response` with sample k >= peak multiplied by exp(-rate x (k - peak) / sample_rate), cut at
// `length`, then everything from `from` on scaled so that the direct over reverberant energy
// is `drr_db` (the band's filters are linear: each part's energy scales with its gain squared).
std::vector<float> Moved(const std::vector<float>& response, std::size_t peak, std::size_t length, double rate,
                         double drr_db, double sample_rate) {
  std::vector<float> out(response.begin(), response.begin() + static_cast<std::ptrdiff_t>(length));
  for (std::size_t k = peak; k < length; ++k) {
    out[k] = static_cast<float>(out[k] * std::exp(-rate * static_cast<double>(k - peak) / sample_rate));
  }
  const std::size_t from = ReverberationStart(peak, length, sample_rate);
  const auto [direct, reverberant] = SplitEnergies(out, from, sample_rate);
  if (!(direct > 0.0) || !(reverberant > 0.0)) {
    throw std::invalid_argument(std::string("moved response: no sound ") + (direct > 0.0 ? "after" : "within") +
                                " its direct sound in 600-5400 Hz");
  }
  const double gain = std::sqrt(direct / (reverberant * std::pow(10.0, drr_db / 10.0)));
  for (std::size_t k = from; k < length; ++k) out[k] = static_cast<float>(gain * out[k]);
  return out;
}

}  // namespace

double DirectOverReverberantDb(const std::vector<float>& response, std::size_t peak, double sample_rate) {
  if (peak >= response.size()) {
    throw std::invalid_argument("direct over reverberant energy: the direct sound's sample " + std::to_string(peak) +
                                " is past the response's " + std::to_string(response.size()));
  }
  const auto [direct, reverberant] =
      SplitEnergies(response, ReverberationStart(peak, response.size(), sample_rate), sample_rate);
  return 10.0 * std::log10(std::max(direct, 1e-300) / std::max(reverberant, 1e-300));
}

std::vector<float> MovedResponse(const std::vector<float>& response, double sample_rate, double rt60, double drr_db) {
  return MovedResponse(response, MeasureResponse(response, sample_rate), sample_rate, rt60, drr_db);
}

std::vector<float> MovedResponse(const std::vector<float>& response, const ResponseMeasures& own, double sample_rate,
                                 double rt60, double drr_db) {
  if (const auto problem = ResponseProblem(own)) throw std::invalid_argument("moved response: the response is " + *problem);
  if (!std::isfinite(rt60) || rt60 <= 0.0 || rt60 > own.rt60_s * (1.0 + kMovedRt60Tolerance)) {
    throw std::invalid_argument("moved response: expected an RT60 above 0 and at most the response's own " +
                                std::to_string(own.rt60_s) + " s (a room is only made to decay faster), got " +
                                std::to_string(rt60));
  }
  if (!std::isfinite(drr_db) || std::abs(drr_db) > kMovedMaxDrrDb) {
    throw std::invalid_argument("moved response: expected a DRR from -" + std::to_string(kMovedMaxDrrDb) + " to " +
                                std::to_string(kMovedMaxDrrDb) + " dB, got " + std::to_string(drr_db));
  }
  const std::size_t length =
      std::min(response.size(), own.peak + static_cast<std::size_t>(std::ceil(kMovedLengthRt60 * rt60 * sample_rate)));
  // An amplitude decaying at `rate` per second takes 60 dB off in 3 ln 10 / rate seconds. The
  // measured decay is not one line, and Schroeder's curve starts with the direct sound, so the
  // rate added is corrected by what the line fit reads of the moved room.
  constexpr double kAmplitudeRateRt60 = 3.0 * 2.302585092994046;
  double rate = std::max(0.0, kAmplitudeRateRt60 * (1.0 / rt60 - 1.0 / own.rt60_s));
  std::vector<float> out = Moved(response, own.peak, length, rate, drr_db, sample_rate);
  for (int pass = 0; pass < 8; ++pass) {
    const double read = MeasureResponse(out, sample_rate).rt60_s;
    if (!std::isfinite(read) || std::abs(read / rt60 - 1.0) <= kMovedRt60Tolerance) break;
    rate = std::max(0.0, rate + kAmplitudeRateRt60 * (1.0 / rt60 - 1.0 / read));
    out = Moved(response, own.peak, length, rate, drr_db, sample_rate);
  }
  return out;
}

}  // namespace nava_modem
