#include "nava_modem/response_splice.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nava_modem/measured_response.h"

namespace nava_modem {
namespace {

// In-band energy of `band` over [from, to), clipped to it.
double Energy(const std::vector<double>& band, long from, long to) {
  double e = 0.0;
  for (long k = std::max(0L, from); k < std::min<long>(to, static_cast<long>(band.size())); ++k) e += band[k] * band[k];
  return e;
}

}  // namespace

std::vector<float> SpliceResponses(const PeakedResponse& head, const PeakedResponse& tail, const PeakedResponse& keep,
                                   std::size_t at, double sample_rate) {
  for (const PeakedResponse* r : {&head, &tail, &keep}) {
    if (r->peak >= r->samples.size()) {
      throw std::invalid_argument("splice: a direct sound at sample " + std::to_string(r->peak) + " of a response of " +
                                  std::to_string(r->samples.size()) + " samples");
    }
  }
  const auto band = [&](const PeakedResponse& r) {
    return ResponseBand(r.samples, sample_rate, kResponseBandLowHz, kResponseBandHighHz);
  };
  // `keep` is usually one of the two (nava_bench --splice keeps A's energies): filtered once.
  const std::vector<double> keep_band = band(keep);
  const std::vector<double> head_own = &head == &keep ? std::vector<double>{} : band(head);
  const std::vector<double> tail_own = &tail == &keep ? std::vector<double>{} : band(tail);
  const std::vector<double>& head_band = &head == &keep ? keep_band : head_own;
  const std::vector<double>& tail_band = &tail == &keep ? keep_band : tail_own;
  const long pre = static_cast<long>(std::min(head.peak, keep.peak));
  const long cut = static_cast<long>(at);
  const long end = static_cast<long>(std::min(tail.samples.size() - tail.peak, keep.samples.size() - keep.peak));
  const auto span = [&](const std::vector<double>& b, std::size_t peak, long from, long to) {
    return Energy(b, static_cast<long>(peak) + from, static_cast<long>(peak) + to);
  };
  const auto gain = [&](double want, double have, const char* part) {
    if (!(want > 0.0) || !(have > 0.0)) {
      throw std::invalid_argument(std::string("splice at ") + std::to_string(1e3 * cut / sample_rate) + " ms: the " + part +
                                  " has no sound in its span (the splice lies past a response's end)");
    }
    return std::sqrt(want / have);
  };
  const double head_gain = gain(span(keep_band, keep.peak, -pre, cut), span(head_band, head.peak, -pre, cut), "head");
  const double tail_gain = gain(span(keep_band, keep.peak, cut, end), span(tail_band, tail.peak, cut, end), "tail");
  const long post = static_cast<long>(std::max(head.samples.size() - head.peak, tail.samples.size() - tail.peak));
  std::vector<float> out(static_cast<std::size_t>(pre + post), 0.0f);
  for (long i = 0; i < static_cast<long>(out.size()); ++i) {
    const long d = i - pre;  // samples after the direct sound
    const bool early = d < cut;
    const PeakedResponse& from = early ? head : tail;
    const long k = static_cast<long>(from.peak) + d;
    if (k >= 0 && k < static_cast<long>(from.samples.size())) {
      out[static_cast<std::size_t>(i)] = static_cast<float>((early ? head_gain : tail_gain) * from.samples[static_cast<std::size_t>(k)]);
    }
  }
  return out;
}

}  // namespace nava_modem
