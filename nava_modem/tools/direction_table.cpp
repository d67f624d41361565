#include "direction_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "nava_bench_support.h"
#include "nava_modem/array_decode.h"
#include "nava_modem/direction_estimator.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/room_array.h"
#include "nava_modem/room_channel.h"
#include "tool_args/number_text.h"
#include "tool_args/parallel_for.h"

namespace nava_modem::tools {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDeg = 180.0 / M_PI;

// The two arrays the simulated microphones stand for.
struct MicArray {
  const char* name;  // the table's key
  const char* geometry;
  std::vector<Microphone2D> mics;
  bool pair;
};

std::vector<MicArray> Arrays() {
  const double half = 0.1 / std::sqrt(2.0);
  return {{"omni", "a square of four microphones, 0.1 m from its centre to each", {{half, half}, {-half, half}, {-half, -half}, {half, -half}}, false},
          {"bidirectional", "a pair 0.2 m apart on the robot's x axis", {{0.1, 0.0}, {-0.1, 0.0}}, true}};
}

// One decoded packet: where it came from, what the array said, how sure it was (rad; estimate
// NaN when the array could not tell).
struct DirectionSample {
  double truth = 0.0, estimate = kNaN, confidence = 0.0;
};

struct DirectionCell {
  double rt60 = 0.0, drr_db = 0.0;
  int sent[2] = {0, 0};
  std::vector<DirectionSample> samples[2];  // per array, in Arrays()'s order
};

// Packets from random bearings in one cell, decoded by one array.
std::vector<DirectionSample> MeasureCell(const ModemProfile& profile, const MicArray& array, const DirectionRequest& r, double rt60,
                                double drr_db, unsigned seed, int* sent) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> bearing(-M_PI, M_PI);
  std::uniform_int_distribution<int> byte(0, 255);
  const double fs = r.options.sample_rate;
  std::vector<DirectionSample> out;
  // Until the cell has its packets sent and at least min_decoded decoded (a link that seldom
  // decodes still needs its directions drawn from somewhere when it does), or max_packets sent.
  int k = 0;
  for (; k < r.max_packets && (k < r.packets || static_cast<int>(out.size()) < r.min_decoded); ++k) {
    std::vector<std::uint8_t> data(kDataBytes);
    for (auto& b : data) b = static_cast<std::uint8_t>(byte(rng));
    // Room behind it for the tail to die away before the receiver's flush.
    const std::vector<float> clean = PacketInSilence(profile, data, 0.4, 0.4 + rt60);
    ArraySource source;
    source.mics = array.mics;
    source.bearing = bearing(rng);
    source.distance = 2.0;
    RoomOptions room;
    room.rt60 = rt60;
    room.drr_db = drr_db;
    room.noise = RoomOptions::Noise::kWhite;
    room.snr_db = r.snr_db;
    room.seed = seed * 1000u + static_cast<unsigned>(k);  // apart from every other cell's: k < 1000 (--max-packets)
    const std::vector<std::vector<float>> heard = RenderRoomArray(clean, fs, room, source);
    const std::vector<RxEvent> events = DecodeArray(profile, {}, heard, array.mics);
    const auto it = std::find_if(events.begin(), events.end(),
                                 [&](const RxEvent& e) { return e.kind == RxEvent::Kind::kPacket && e.data == data; });
    if (it == events.end()) continue;
    out.push_back({source.bearing, it->direction, std::isfinite(it->direction) ? it->direction_confidence : 0.0});
  }
  if (sent) *sent = k;
  return out;
}

// The square's errors (deg, 180 for no direction) and the pair's bits, as one line's figures.
struct DirectionSummary {
  int decoded = 0;
  double median = kNaN, p90 = kNaN;  // square
  int right = 0, wrong = 0, none = 0;  // pair
};

DirectionSummary Summarise(const std::vector<DirectionSample>& samples, bool pair, double axis) {
  DirectionSummary s;
  s.decoded = static_cast<int>(samples.size());
  std::vector<double> errors;
  for (const DirectionSample& x : samples) {
    if (pair) {
      if (!std::isfinite(x.estimate)) ++s.none;
      else if (SameEndOfAxis(x.truth, x.estimate, axis)) ++s.right;
      else ++s.wrong;
    } else {
      errors.push_back(std::isfinite(x.estimate) ? std::abs(std::remainder(x.estimate - x.truth, 2.0 * M_PI)) * kDeg : 180.0);
    }
  }
  s.median = Percentile(errors, 0.5);
  s.p90 = Percentile(errors, 0.9);
  return s;
}

void WriteTable(const DirectionRequest& r, const std::vector<DirectionCell>& cells) {
  FILE* f = std::fopen(r.errors_out.c_str(), "w");
  if (!f) throw std::runtime_error("--errors-out " + r.errors_out + ": cannot write it");
  std::fprintf(f,
               "# What the %s receiver's microphone arrays report of where a packet came from, by the room's\n"
               "# RT60 and DRR: every decoded packet's [true bearing, estimate, confidence] (degrees in the\n"
               "# array's frame; estimate .nan where the array could not tell), rendered by nava_room's array\n"
               "# renderer. The simulated omni and bidirectional microphones draw their reports from it\n"
               "# (audio_propagation/direction_errors.h).\n",
               ProfileName(r.profile));
  std::fprintf(f, "profile: %s\n", ProfileName(r.profile));
  std::string rt60s, drrs;
  for (double v : r.rt60) rt60s += (rt60s.empty() ? "" : ",") + multirobot_audio::tools::NumberText(v);
  for (double v : r.drr_db) drrs += (drrs.empty() ? "" : ",") + multirobot_audio::tools::NumberText(v);
  std::fprintf(f,
               "command: \"nava_bench --direction --profile %s --packets %d --min-decoded %d --max-packets %d --snr %s --rt60 %s "
               "--drr %s --seed %u --rate %.0f --errors-out %s\"\n",
               ProfileName(r.profile), r.packets, r.min_decoded, r.max_packets, multirobot_audio::tools::NumberText(r.snr_db).c_str(), rt60s.c_str(),
               drrs.c_str(), r.seed, r.options.sample_rate, r.errors_out.c_str());
  std::fprintf(f, "snr_db: %s\npackets: %d\nmin_packets: %d\nrt60_s: [%s]\ndrr_db: [%s]\n", multirobot_audio::tools::NumberText(r.snr_db).c_str(),
               r.packets, std::max(1, r.min_decoded), rt60s.c_str(), drrs.c_str());
  const std::vector<MicArray> arrays = Arrays();
  std::fprintf(f, "arrays:\n");
  for (const MicArray& a : arrays) std::fprintf(f, "  %s: \"%s\"\n", a.name, a.geometry);
  std::fprintf(f, "cells:\n");
  for (const DirectionCell& c : cells) {
    std::fprintf(f, "  - rt60_s: %s\n    drr_db: %s\n    sent: {omni: %d, bidirectional: %d}\n", multirobot_audio::tools::NumberText(c.rt60).c_str(),
                 multirobot_audio::tools::NumberText(c.drr_db).c_str(), c.sent[0], c.sent[1]);
    for (std::size_t a = 0; a < arrays.size(); ++a) {
      std::fprintf(f, "    %s: [", arrays[a].name);
      for (std::size_t k = 0; k < c.samples[a].size(); ++k) {
        const DirectionSample& s = c.samples[a][k];
        char estimate[32];
        if (std::isfinite(s.estimate)) std::snprintf(estimate, sizeof estimate, "%.1f", s.estimate * kDeg);
        else std::snprintf(estimate, sizeof estimate, ".nan");
        std::fprintf(f, "%s[%.1f, %s, %.2f]", k ? ", " : "", s.truth * kDeg, estimate, s.confidence);
      }
      std::fprintf(f, "]\n");
    }
  }
  if (std::fclose(f) != 0) throw std::runtime_error("--errors-out " + r.errors_out + ": writing it failed");
}

// A dummy head's response file: its path and the head's azimuth (deg), from a name that ends in
// `headaz<signed degrees>`.
struct HeadFile {
  std::string path, name;
  double head_azimuth = 0.0;
};

// The head's azimuth (deg) in a name ending in `headaz<signed degrees>.wav`, else nothing.
// (By hand: <regex> trips GCC 12's maybe-uninitialized warning in the sanitized build.)
std::optional<double> HeadAzimuth(const std::string& name) {
  const std::string key = "headaz", suffix = ".wav";
  const std::size_t at = name.rfind(key);
  if (at == std::string::npos || name.size() < suffix.size() ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return std::nullopt;
  }
  const std::string number = name.substr(at + key.size(), name.size() - suffix.size() - at - key.size());
  if (number.empty() || number.find_first_not_of("+-.0123456789") != std::string::npos) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (end != number.c_str() + number.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::vector<HeadFile> HeadFiles(const std::string& dir, const multirobot_audio::tools::ToolUsage& usage) {
  DIR* d = opendir(dir.c_str());
  if (!d) usage.Fail("--binaural-dir " + dir + ": cannot read the folder");
  std::vector<HeadFile> files;
  while (const dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    if (const std::optional<double> azimuth = HeadAzimuth(name)) files.push_back({dir + "/" + name, name, *azimuth});
  }
  closedir(d);
  std::sort(files.begin(), files.end(), [](const HeadFile& a, const HeadFile& b) { return a.name < b.name; });
  if (files.empty()) {
    usage.Fail("--binaural-dir " + dir + ": no two-channel response named ..._headaz<degrees>.wav (a dummy head turned by that "
               "azimuth, left ear first)");
  }
  return files;
}

// A dummy head's two ears as a pair on the head's y axis (left ear at +y). 0.15 m apart: the
// ears' spacing on the KEMAR and similar heads; the head between them delays the far ear a
// little more than free air would, which only widens the difference the pair measures.
constexpr double kEarHalfSpacing = 0.075;

// The measured pair: packets through each dummy head's two ears, the bit judged on the ears'
// axis, beside the rendered cell nearest the ears' mean RT60 and DRR.
void MeasuredPairs(const ModemProfile& profile, const DirectionRequest& r, const std::vector<DirectionCell>& cells,
                   const multirobot_audio::tools::ToolUsage& usage) {
  const double fs = r.options.sample_rate;
  const std::vector<Microphone2D> ears = {{0.0, kEarHalfSpacing}, {0.0, -kEarHalfSpacing}};
  std::printf("\nmeasured pairs (%s): a dummy head's ears as a pair 0.15 m apart across the head, %d packets a file, "
              "white noise at SNR %.0f dB per ear; the source at minus the head's azimuth\n",
              r.binaural_dir.c_str(), r.packets, r.snr_db);
  std::printf("%-44s %8s %7s %7s %8s %6s %6s %6s   %s\n", "file", "bearing", "rt60_s", "drr_dB", "decoded", "right", "wrong",
              "none", "rendered cell (right/wrong/none of decoded, the bearings within 20 deg of it)");
  int total_right = 0, total_judged = 0, cell_right = 0, cell_judged = 0;
  for (const HeadFile& file : HeadFiles(r.binaural_dir, usage)) {
    std::vector<std::vector<float>> responses;
    ResponseMeasures mean{};
    for (int ear = 0; ear < 2; ++ear) {
      try {
        responses.push_back(LoadImpulseResponse(file.path, ear, fs));
      } catch (const std::exception& e) {
        usage.Fail(std::string("--binaural-dir: ") + e.what());
      }
      const ResponseMeasures m = MeasureResponse(responses.back(), fs);
      mean.rt60_s += 0.5 * m.rt60_s;
      mean.drr_db += 0.5 * m.drr_db;
    }
    const double truth = -file.head_azimuth / kDeg;
    std::mt19937 rng(r.seed);
    const CleanSignal clean = RandomPackets(profile, r.packets, 0.6, 0.4, rng);
    std::vector<std::vector<float>> heard;
    for (int ear = 0; ear < 2; ++ear) {
      RoomOptions o;
      o.response = responses[static_cast<std::size_t>(ear)];
      o.noise = RoomOptions::Noise::kWhite;
      o.snr_db = r.snr_db;
      o.seed = r.seed * 31u + static_cast<unsigned>(ear);
      heard.push_back(RenderRoom(clean.samples, fs, o));
    }
    const std::size_t length = std::min(heard[0].size(), heard[1].size());
    for (auto& h : heard) h.resize(length);
    const std::vector<RxEvent> events = DecodeArray(profile, {}, heard, ears);
    int decoded = 0, right = 0, wrong = 0, none = 0;
    for (const RxEvent& e : events) {
      if (e.kind != RxEvent::Kind::kPacket ||
          std::find(clean.sent.begin(), clean.sent.end(), HexBytes(e.data)) == clean.sent.end()) {
        continue;
      }
      ++decoded;
      if (!std::isfinite(e.direction)) ++none;
      else if (SameEndOfAxis(truth, e.direction, M_PI / 2)) ++right;
      else ++wrong;
    }
    // The rendered pair lies on x; the head's ears on y: compare bearings off each pair's axis.
    const DirectionCell* nearest = &cells.front();
    for (const DirectionCell& c : cells) {
      const double d = std::abs(std::log(c.rt60 / mean.rt60_s)) * 10.0 + std::abs(c.drr_db - mean.drr_db);
      const double best = std::abs(std::log(nearest->rt60 / mean.rt60_s)) * 10.0 + std::abs(nearest->drr_db - mean.drr_db);
      if (d < best) nearest = &c;
    }
    const double off_axis = std::abs(std::remainder(truth - M_PI / 2, M_PI));  // rad from the ears' axis
    int c_right = 0, c_wrong = 0, c_none = 0;
    for (const DirectionSample& s : nearest->samples[1]) {
      if (std::abs(std::abs(std::remainder(s.truth, M_PI)) - off_axis) > 20.0 / kDeg) continue;
      if (!std::isfinite(s.estimate)) ++c_none;
      else if (SameEndOfAxis(s.truth, s.estimate, 0.0)) ++c_right;
      else ++c_wrong;
    }
    std::printf("%-44s %+8.0f %7.2f %+7.1f %5d/%-2d %6d %6d %6d   rt60 %.1f drr %+.0f: %d/%d/%d\n", file.name.c_str(),
                truth * kDeg, mean.rt60_s, mean.drr_db, decoded, r.packets, right, wrong, none, nearest->rt60,
                nearest->drr_db, c_right, c_wrong, c_none);
    // Broadside (the head facing the source) has no right side: not counted.
    if (std::abs(std::sin(truth)) > std::sin(20.0 / kDeg)) {
      total_right += right;
      total_judged += decoded;
      cell_right += c_right;
      cell_judged += c_right + c_wrong + c_none;
    }
  }
  std::printf("measured pairs off broadside: bit right in %d of %d decoded (%.0f %%); the rendered cells at those bearings: "
              "%d of %d (%.0f %%)\n",
              total_right, total_judged, total_judged ? 100.0 * total_right / total_judged : kNaN, cell_right, cell_judged,
              cell_judged ? 100.0 * cell_right / cell_judged : kNaN);
}

}  // namespace

int DirectionTable(const DirectionRequest& request, const multirobot_audio::tools::ToolUsage& usage) {
  const std::unique_ptr<ModemProfile> profile = MakeProfile(request.profile, request.options);
  const std::vector<MicArray> arrays = Arrays();
  std::vector<DirectionCell> cells;
  for (double rt60 : request.rt60) {
    for (double drr : request.drr_db) cells.push_back({rt60, drr, {0, 0}, {}});
  }
  std::printf("nava_bench --direction: %d %s packets per cell and array (more, up to %d, until %d are decoded) from random bearings at %.0f Hz, white noise at "
              "SNR %.0f dB per microphone; omni: %s; bidirectional: %s\n",
              request.packets, ProfileName(request.profile), request.max_packets, request.min_decoded, request.options.sample_rate, request.snr_db, arrays[0].geometry,
              arrays[1].geometry);
  // Each cell and array its own seed, so that the table does not depend on the thread count.
  multirobot_audio::tools::ParallelFor(cells.size() * arrays.size(), request.threads, [&](std::size_t job) {
    DirectionCell& c = cells[job / arrays.size()];
    const std::size_t a = job % arrays.size();
    c.samples[a] = MeasureCell(*profile, arrays[a], request, c.rt60, c.drr_db,
                               request.seed * 7919u + static_cast<unsigned>(job), &c.sent[a]);
  });
  std::printf("%7s %7s | %-34s | %-38s\n", "rt60_s", "drr_dB", "omni: decoded/sent median p90 (deg)",
              "bidirectional: decoded/sent right wrong none");
  for (const DirectionCell& c : cells) {
    const DirectionSummary omni = Summarise(c.samples[0], false, 0.0), pair = Summarise(c.samples[1], true, 0.0);
    std::printf("%7.2f %+7.0f | %6d/%-6d %9.1f %9.1f | %6d/%-6d %7d %5d %5d\n", c.rt60, c.drr_db, omni.decoded, c.sent[0],
                omni.median, omni.p90, pair.decoded, c.sent[1], pair.right, pair.wrong, pair.none);
  }
  if (!request.binaural_dir.empty()) MeasuredPairs(*profile, request, cells, usage);
  if (!request.errors_out.empty()) {
    // A cell with fewer than min_decoded packets draws in the simulation from its DRR at the
    // nearest RT60 that has enough, else a drier DRR's (audio_propagation/direction_errors.h):
    // the driest DRR needs one with enough.
    const std::size_t enough = static_cast<std::size_t>(std::max(1, request.min_decoded));
    std::string thin;
    for (std::size_t a = 0; a < arrays.size(); ++a) {
      bool driest = false;
      for (const DirectionCell& c : cells) {
        if (c.samples[a].size() >= enough) {
          driest = driest || c.drr_db == request.drr_db.back();
          continue;
        }
        thin += " " + std::string(arrays[a].name) + " at RT60 " + multirobot_audio::tools::NumberText(c.rt60) + " s, DRR " + multirobot_audio::tools::NumberText(c.drr_db) +
                " dB (" + std::to_string(c.samples[a].size()) + ");";
      }
      if (!driest) {
        std::fprintf(stderr, "nava_bench: --errors-out %s: no cell at the driest DRR (%g dB) decoded %zu packets by the %s "
                             "array (more --max-packets, or a drier grid)\n",
                     request.errors_out.c_str(), request.drr_db.back(), enough, arrays[a].name);
        return 1;
      }
    }
    if (!thin.empty()) {
      std::printf("cells under %zu packets (the simulation draws from their DRR at the nearest RT60 with enough):%s\n", enough,
                  thin.c_str());
    }
    WriteTable(request, cells);
    std::printf("wrote %s\n", request.errors_out.c_str());
  }
  return 0;
}

}  // namespace nava_modem::tools
