#include "splice_table.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "nava_modem/measured_response.h"
#include "nava_modem/response_splice.h"
#include "nava_modem/wav_file.h"

namespace nava_modem::tools {
namespace {

// `path[:K]` (K a channel, 0 to 1023) loaded at `sample_rate`, or the tool fails naming `flag`.
PeakedResponse Load(const std::string& flag, const std::string& spec, double sample_rate,
                    const multirobot_audio::tools::ToolUsage& usage) {
  std::string path = spec;
  std::optional<int> channel;
  const std::size_t colon = spec.rfind(':');
  if (colon != std::string::npos && colon + 1 < spec.size() &&
      std::all_of(spec.begin() + static_cast<std::ptrdiff_t>(colon) + 1, spec.end(), [](unsigned char c) { return std::isdigit(c); })) {
    errno = 0;
    const long k = std::strtol(spec.c_str() + colon + 1, nullptr, 10);
    if (errno != 0 || k > 1023) usage.Fail(flag + " " + spec + ": expected a channel from 0 to 1023 after the ':'");
    path = spec.substr(0, colon);
    channel = static_cast<int>(k);
  }
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

int SpliceTable(const SpliceRequest& request, const multirobot_audio::tools::ToolUsage& usage) {
  const double fs = request.sample_rate;
  const PeakedResponse a = Load("--early", request.early, fs, usage), b = Load("--late", request.late, fs, usage);
  std::error_code error;
  std::filesystem::create_directories(request.out_dir, error);
  if (error) usage.Fail("--out " + request.out_dir + ": " + error.message());
  std::printf("splice: A = %s, B = %s; each part at A's energy over its span (read each file's DRR and RT60)\n",
              request.early.c_str(), request.late.c_str());
  std::printf("%-24s %7s %7s\n", "response", "rt60_s", "drr_dB");
  const auto write = [&](const std::string& name, const std::vector<float>& samples) {
    WriteFloatWavFile((std::filesystem::path(request.out_dir) / name).string(), samples, fs);
    const ResponseMeasures m = MeasureResponse(samples, fs);
    std::printf("%-24s %7.2f %+7.1f\n", name.c_str(), m.rt60_s, m.drr_db);
  };
  write("a.wav", a.samples);
  write("b.wav", b.samples);
  for (const double ms : request.at_ms) {
    const std::size_t at = static_cast<std::size_t>(std::lround(ms * 1e-3 * fs));
    try {
      const std::vector<float> ab = SpliceResponses(a, b, a, at, fs), ba = SpliceResponses(b, a, a, at, fs);
      write("a" + MsName(ms) + "_b.wav", ab);
      write("b" + MsName(ms) + "_a.wav", ba);
    } catch (const std::invalid_argument& e) {
      usage.Fail("--at-ms " + MsName(ms) + ": " + e.what());
    }
  }
  return 0;
}

}  // namespace nava_modem::tools
