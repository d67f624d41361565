#pragma once

// What nava_bench needs around the decoders (which it runs with bench_support's Run): the
// packets they printed, and scoring those against what was sent.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "nava_modem/frame.h"
#include "nava_modem/modem_profile.h"

namespace nava_modem::tools {

struct Count {
  int right = 0, wrong = 0;
};

// Counts each sent packet at most once.
inline Count Score(const std::vector<std::string>& decoded_hex, const std::vector<std::string>& sent_hex) {
  std::map<std::string, int> left;
  for (const std::string& s : sent_hex) ++left[s];
  Count c;
  for (const std::string& d : decoded_hex) {
    auto it = left.find(d);
    if (it != left.end() && it->second > 0) {
      --it->second;
      ++c.right;
    } else if (it == left.end()) {
      ++c.wrong;
    }
  }
  return c;
}

inline std::vector<std::string> NavaPackets(const std::string& json_lines) {
  std::vector<std::string> out;
  std::istringstream in(json_lines);
  std::string line;
  while (std::getline(in, line)) {
    if (line.find("\"kind\": \"packet\"") == std::string::npos) continue;
    const auto at = line.find("\"data\": \"");
    if (at != std::string::npos) out.push_back(line.substr(at + 9, 8));
  }
  return out;
}

// minimodem prints the bytes it decodes; our packets are the runs of 7 that frame correctly.
inline std::vector<std::string> MinimodemPackets(const std::string& bytes, CrcVariant crc) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i + kFrameBytes <= bytes.size(); ++i) {
    Frame f;
    for (int k = 0; k < kFrameBytes; ++k) f[k] = static_cast<std::uint8_t>(bytes[i + k]);
    if (f[0] != kHeader || !CrcMatches(f, crc)) continue;
    out.push_back(HexBytes({f[1], f[2], f[3], f[4]}));
    i += kFrameBytes - 1;
  }
  return out;
}

inline std::string SelfDir() {
  char path[4096];
  const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) return ".";
  const std::string p(path, static_cast<std::size_t>(n));
  return p.substr(0, p.rfind('/'));
}


// N packets of random data with gaps of `gap` s (plus up to `jitter` s more, so that packets
// meet an interferer at different moments), and the data sent, as hex.
struct CleanSignal {
  std::vector<float> samples;
  std::vector<std::string> sent;
  std::vector<std::size_t> ends;  // where each packet's gap after it ends
  double seconds = 0.0;
};
inline CleanSignal RandomPackets(const ModemProfile& profile, int packets, double gap, double jitter, std::mt19937& rng) {
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_real_distribution<double> extra(0.0, jitter);
  const double rate = profile.options().sample_rate;
  CleanSignal c;
  c.samples.assign(static_cast<std::size_t>(gap * rate), 0.0f);
  for (int p = 0; p < packets; ++p) {
    std::vector<std::uint8_t> data(kDataBytes);
    for (auto& b : data) b = static_cast<std::uint8_t>(byte(rng));
    c.sent.push_back(HexBytes(data));
    const std::vector<float> burst = profile.ModulatePacket(data);
    c.samples.insert(c.samples.end(), burst.begin(), burst.end());
    c.samples.insert(c.samples.end(), static_cast<std::size_t>((gap + extra(rng)) * rate), 0.0f);
    c.ends.push_back(c.samples.size());
  }
  c.seconds = c.samples.size() / rate;
  return c;
}

// One packet of `data` with `before` s of silence ahead of it and `after` s behind.
inline std::vector<float> PacketInSilence(const ModemProfile& profile, const std::vector<std::uint8_t>& data, double before,
                                          double after) {
  const double rate = profile.options().sample_rate;
  std::vector<float> clean(static_cast<std::size_t>(before * rate), 0.0f);
  const std::vector<float> burst = profile.ModulatePacket(data);
  clean.insert(clean.end(), burst.begin(), burst.end());
  clean.insert(clean.end(), static_cast<std::size_t>(after * rate), 0.0f);
  return clean;
}

// The p-quantile (nearest rank) of `v`, sorted in place; NaN for none.
inline double Percentile(std::vector<double>& v, double p) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(std::floor(p * (v.size() - 1) + 0.5)))];
}

}  // namespace nava_modem::tools
