#include "response_splice.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "nava_modem/measured_response.h"
#include "nava_modem/wav_file.h"

namespace nava_modem::tools {
namespace {

// In-band energy of `x` over [from, to) (indices clipped to x).
double BandEnergy(const std::vector<double>& band, long from, long to) {
  double e = 0.0;
  for (long k = std::max(0L, from); k < std::min<long>(to, static_cast<long>(band.size())); ++k) e += band[k] * band[k];
  return e;
}

std::vector<double> Band(const std::vector<float>& x, double sample_rate) {
  return ResponseBand(x, sample_rate, kResponseBandLowHz, kResponseBandHighHz);
}

// `path[:K]` into the path and channel K (none: the file must be mono).
std::pair<std::string, std::optional<int>> PathAndChannel(const std::string& spec) {
  const std::size_t colon = spec.rfind(':');
  if (colon == std::string::npos || colon + 1 == spec.size() ||
      !std::all_of(spec.begin() + static_cast<std::ptrdiff_t>(colon) + 1, spec.end(), [](unsigned char c) { return std::isdigit(c); })) {
    return {spec, std::nullopt};
  }
  return {spec.substr(0, colon), std::stoi(spec.substr(colon + 1))};
}

PeakedResponse Load(const std::string& flag, const std::string& spec, double sample_rate,
                    const multirobot_audio::tools::ToolUsage& usage) {
  const auto [path, channel] = PathAndChannel(spec);
  try {
    PeakedResponse r;
    r.samples = LoadImpulseResponse(path, channel, sample_rate);
    r.peak = MeasureResponse(r.samples, sample_rate).peak;
    return r;
  } catch (const std::exception& e) {
    usage.Fail(flag + " " + spec + ": " + e.what());
  }
}

std::string MsName(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", ms);
  return text;
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
  const long pre = static_cast<long>(std::min({head.peak, tail.peak, keep.peak}));
  const long post = static_cast<long>(std::max(head.samples.size() - head.peak, tail.samples.size() - tail.peak));
  const long cut = static_cast<long>(at);
  const std::vector<double> head_band = Band(head.samples, sample_rate), tail_band = Band(tail.samples, sample_rate),
                            keep_band = Band(keep.samples, sample_rate);
  const auto before = [&](const std::vector<double>& band, std::size_t peak) {
    return BandEnergy(band, static_cast<long>(peak) - pre, static_cast<long>(peak) + cut);
  };
  const auto after = [&](const std::vector<double>& band, std::size_t peak) {
    return BandEnergy(band, static_cast<long>(peak) + cut, static_cast<long>(band.size()));
  };
  const auto gain = [](double want, double have) { return have > 0.0 ? std::sqrt(want / have) : 0.0; };
  const double head_gain = gain(before(keep_band, keep.peak), before(head_band, head.peak));
  const double tail_gain = gain(after(keep_band, keep.peak), after(tail_band, tail.peak));
  std::vector<float> out(static_cast<std::size_t>(pre + post), 0.0f);
  for (long i = 0; i < static_cast<long>(out.size()); ++i) {
    const long d = i - pre;  // samples after the direct sound
    const PeakedResponse& from = d < cut ? head : tail;
    const long k = static_cast<long>(from.peak) + d;
    if (k >= 0 && k < static_cast<long>(from.samples.size())) {
      out[static_cast<std::size_t>(i)] = static_cast<float>((d < cut ? head_gain : tail_gain) * from.samples[static_cast<std::size_t>(k)]);
    }
  }
  return out;
}

int SpliceTable(const SpliceRequest& request, const multirobot_audio::tools::ToolUsage& usage) {
  const double fs = request.sample_rate;
  const PeakedResponse a = Load("--early", request.early, fs, usage), b = Load("--late", request.late, fs, usage);
  std::error_code error;
  std::filesystem::create_directories(request.out_dir, error);
  if (error) usage.Fail("--out " + request.out_dir + ": " + error.message());
  std::printf("splice: A = %s, B = %s; each spliced response has A's energy before and after the splice\n", request.early.c_str(),
              request.late.c_str());
  std::printf("%-24s %7s %7s\n", "response", "rt60_s", "drr_dB");
  const auto write = [&](const std::string& name, const std::vector<float>& samples) {
    const std::string path = (std::filesystem::path(request.out_dir) / name).string();
    WriteFloatWavFile(path, samples, fs);
    const ResponseMeasures m = MeasureResponse(samples, fs);
    std::printf("%-24s %7.2f %+7.1f\n", name.c_str(), m.rt60_s, m.drr_db);
  };
  write("a.wav", a.samples);
  write("b.wav", b.samples);
  for (const double ms : request.at_ms) {
    const std::size_t at = static_cast<std::size_t>(std::lround(ms * 1e-3 * fs));
    write("a" + MsName(ms) + "_b.wav", SpliceResponses(a, b, a, at, fs));
    write("b" + MsName(ms) + "_a.wav", SpliceResponses(b, a, a, at, fs));
  }
  return 0;
}

}  // namespace nava_modem::tools
