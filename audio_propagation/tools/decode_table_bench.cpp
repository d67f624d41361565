#include "decode_table_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <set>
#include <string>

#include "audio_propagation/decode_table.h"
#include "bench_support/child_process.h"
#include "bench_support/speech.h"
#include "nava_modem/frame.h"
#include "nava_modem/moved_rooms.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/room_phy.h"
#include "measured_rooms.h"
#include "model_calibration.h"
#include "parallel_cells.h"
#include "table_cells.h"
#include "whine_harm.h"
#include "tool_args/tool_args.h"

namespace audio_propagation::tools {
namespace {

using namespace nava_modem;
using bench_support::CpuNow;
using bench_support::MakeSpeech;
using bench_support::SpeechFrom;
using bench_support::TempDir;

using audio_propagation::DecodeOutcome;
using audio_propagation::DecodeTable;
using audio_propagation::Interference;

constexpr Interference kKinds[] = {Interference::kWhite, Interference::kPink, Interference::kSpeech,
                                   Interference::kWhine, Interference::kPacket};
std::size_t Nearest(const std::vector<double>& axis, double x) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < axis.size(); ++k) {
    if (std::fabs(axis[k] - x) < std::fabs(axis[best] - x)) best = k;
  }
  return best;
}

// Delivery against SNR for each kind at one rt60 and DRR, and how often delivery falls as the
// SNR rises by two packets or more (the measurement's scatter, or a receiver's quirk).
void PrintSummary(const DecodeTable& t) {
  const std::size_t r = Nearest(t.rt60, 0.6), d = Nearest(t.drr_db, 0.0);
  std::printf("packets decoded (%%) against SNR (dB), rt60 %g s, drr %g dB, %d packets a cell:\n%-8s", t.rt60[r],
              t.drr_db[d], t.packets, "kind");
  for (double snr : t.snr_db) std::printf("%6g", snr);
  std::printf("\n");
  for (Interference kind : kKinds) {
    std::printf("%-8s", audio_propagation::InterferenceName(kind));
    for (std::size_t k = 0; k < t.snr_db.size(); ++k) std::printf("%6.0f", 100.0 * t.At(kind, r, d, k).packet);
    std::printf("\n");
  }
  int falls = 0, steps = 0;
  for (Interference kind : kKinds) {
    for (std::size_t rt = 0; rt < t.rt60.size(); ++rt) {
      for (std::size_t drr = 0; drr < t.drr_db.size(); ++drr) {
        for (std::size_t k = 1; k < t.snr_db.size(); ++k) {
          ++steps;
          falls += t.At(kind, rt, drr, k).packet <= t.At(kind, rt, drr, k - 1).packet - 1.5 / t.packets;
        }
      }
    }
  }
  std::printf("delivery falls by 2 packets or more as the SNR rises: %d of %d steps\n", falls, steps);
}

// The whine harm curve's frequencies and SIRs: the full ones, or --quick's three of each.
WhineHarmOptions HarmOptions(const DecodeTableRequest& request) {
  WhineHarmOptions o;
  o.threads = request.threads;
  if (request.quick) {
    o.low_hz = 1200.0, o.high_hz = 2300.0, o.step_hz = 1100.0;
    o.low_sir_db = -12.0, o.high_sir_db = 12.0, o.sir_step_db = 12.0;
  }
  return o;
}

int SaveTable(const std::string& out, const DecodeTable& t) {
  try {
    audio_propagation::SaveDecodeTable(out, t);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "decode_table_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}

// --whine-harm: the curve measured anew into a copy of a table, its cells kept.
int AddWhineHarm(const DecodeTableRequest& request) {
  DecodeTable table;
  try {
    table = LoadDecodeTable(request.table_file.empty() ? ShippedDecodeTable("nava") : request.table_file, "nava");
  } catch (const std::exception& e) {
    request.usage.Fail(e.what());
  }
  const std::filesystem::path folder = std::filesystem::path(request.out).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder)) request.usage.Fail("--out: no folder " + folder.string());
  CellSetup s;
  s.profile = Profile::kNava;
  s.seed = request.seed;
  s.model = table.rooms;
  s.table = table;
  s.table.packets = request.packets;
  MeasureWhineHarm(s, HarmOptions(request), table);
  table.command += "; whine harm: " + request.command;
  if (const int failed = SaveTable(request.out, table)) return failed;
  std::printf("table: %s; %.0f s CPU\n", request.out.c_str(), CpuNow());
  return 0;
}

}  // namespace

int DecodeTableBench(const DecodeTableRequest& request) {
  if (request.calibrate) return CalibrateModel(request);
  if (request.whine_harm) return AddWhineHarm(request);
  const multirobot_audio::tools::ToolUsage& usage = request.usage;
  CellSetup s;
  s.profile = request.profile;
  s.model = request.model;
  DecodeTable& t = s.table;
  t.profile = ProfileName(s.profile);
  t.packets = request.packets;
  const int threads = request.threads;
  s.seed = request.seed;
  const std::string& out = request.out;
  const std::filesystem::path folder = std::filesystem::path(out).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder)) usage.Fail("--out: no folder " + folder.string());
  t.command = request.command;
  t.rooms = request.model;
  if (request.quick) {
    t.snr_db = {-12, 0, 12};
    t.drr_db = {-18, 0, 18};
    t.rt60 = {0.5};
  } else {
    t.snr_db = {-15, -12, -9, -6, -3, 0, 3, 6, 9, 12, 18, 30};
    // The room profile still decodes nearly every packet at -15 dB (its long symbols and code
    // gain ~29 dB over the full band's SNR), and the channel model holds the lowest SNR's figures
    // below it: its axis goes down to where it stops.
    if (s.profile == Profile::kRoom) t.snr_db.insert(t.snr_db.begin(), {-27, -24, -21, -18});
    t.drr_db = {-30, -24, -18, -12, -6, 0, 6, 12, 24};
    t.rt60 = {0.3, 0.6, 1.2};
  }
  if (!request.snr_db.empty()) t.snr_db = request.snr_db;
  if (!request.rt60.empty()) t.rt60 = request.rt60;
  // The band: the nava tones and ~150 Hz about each (a bit's main lobe is +-300 Hz wide, the
  // receiver's filters narrower), or the room profile's chirp. The whine sits in the band where
  // a motor's would hurt most without sitting on a tone: midway between nava's two tones, and
  // at 2500 Hz for room (its harmonics at 5000 Hz in the band too).
  if (s.profile == Profile::kNava) {
    t.band_low_hz = std::min(s.modem.mark_hz, s.modem.space_hz) - 150.0;
    t.band_high_hz = std::max(s.modem.mark_hz, s.modem.space_hz) + 150.0;
    t.whine_hz = (s.modem.mark_hz + s.modem.space_hz) / 2.0;
  } else {
    t.band_low_hz = room_phy::kChirpLowHz;
    t.band_high_hz = room_phy::kHighestHz;
    t.whine_hz = 2500.0;
  }
  t.Resize();
  if (request.model == RoomOptions::Model::kMeasured) {
    try {
      s.moved = std::make_shared<const MovedRooms>(nava_modem::tools::MovableRooms(request.rir_dir, s.modem.sample_rate, usage),
                                                   s.modem.sample_rate);
      for (std::size_t k : s.moved->excluded()) {
        std::fprintf(stderr, "not moved: %s (an arrival %.1f dB under its loudest peak before it)\n",
                     s.moved->rooms()[k].name.c_str(), -s.moved->rooms()[k].figures.before_db);
      }
      for (double rt60 : t.rt60) {
        const std::vector<std::size_t> candidates = s.moved->Candidates(rt60);
        std::set<std::string> groups;
        for (std::size_t k : candidates) groups.insert(s.moved->rooms()[k].group);
        std::fprintf(stderr, "rooms moved to RT60 %g s (%zu places in %zu rooms):", rt60, candidates.size(), groups.size());
        for (std::size_t k : candidates) {
          std::fprintf(stderr, " %s (%.2f s)", s.moved->rooms()[k].name.c_str(), s.moved->rooms()[k].figures.rt60_s);
        }
        std::fprintf(stderr, "\n");
      }
    } catch (const std::invalid_argument& e) {
      usage.Fail(std::string("--rir-dir: ") + e.what());
    }
  }
  // Made only now, so that bad arguments leave no folder behind.
  s.speech = ReadAudioAt(MakeSpeech(TempDir(usage, request.dir), s.seed), s.modem.sample_rate);

  const std::size_t per_kind = t.rt60.size() * t.drr_db.size() * t.snr_db.size();
  const std::size_t cells = t.cells.size();
  std::fprintf(stderr, "decode_table_bench --profile %s: %zu cells of %d packets on %d threads\n", t.profile.c_str(), cells,
               t.packets, threads);
  std::vector<CellCounts> counts(cells);
  const auto started = std::chrono::steady_clock::now();
  ParallelCells(
      cells, threads, [&] { return MakeProfile(s.profile, s.modem); },
      [&](const std::unique_ptr<ModemProfile>& mine, std::size_t c) {
        const std::size_t kind = c / per_kind, r = c / (t.drr_db.size() * t.snr_db.size()) % t.rt60.size();
        const std::size_t d = c / t.snr_db.size() % t.drr_db.size(), snr = c % t.snr_db.size();
        counts[c] = MeasureCell(s, *mine, c, kKinds[kind], t.rt60[r], t.drr_db[d], t.snr_db[snr]);
      },
      [&](std::size_t done) {
        if (done % std::max<std::size_t>(1, cells / 50) == 0 || done == cells) {
          const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
          std::fprintf(stderr, "  %zu/%zu cells, %.0f s, about %.0f s to go\n", done, cells, elapsed,
                       elapsed * static_cast<double>(cells - done) / static_cast<double>(done));
        }
      });

  int false_packets = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    const CellCounts& n = counts[c];
    const double all = t.packets;
    t.cells[c] = DecodeOutcome{n.heard[0] / all, n.heard[1] / all, n.heard[2] / all, n.heard[3] / all};
    false_packets += n.false_packets;
  }
  // Saved before the whine harm curve, so that a curve that cannot be read loses no cells.
  if (const int failed = SaveTable(out, t)) return failed;
  // nava's whine cells are at one frequency; the curve tells the model how others compare. A
  // --quick table (for tests) goes without one: its few packets make no curve.
  if (s.profile == Profile::kNava && !request.quick) {
    CellSetup harm = s;
    harm.table.packets = kWhineHarmPackets;
    MeasureWhineHarm(harm, HarmOptions(request), t);
    if (const int failed = SaveTable(out, t)) return failed;
  }
  PrintSummary(t);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf("false packets (CRC passed, data never sent): %d of %zu\n", false_packets,
              cells * static_cast<std::size_t>(t.packets));
  std::printf("table: %s; %.0f s wall, %.0f s CPU on %d threads\n", out.c_str(), wall, CpuNow(), threads);
  return 0;
}

}  // namespace audio_propagation::tools

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool([&] {
    return audio_propagation::tools::DecodeTableBench(
        audio_propagation::tools::ParseDecodeTableBenchArgs(multirobot_audio::tools::Words(argc, argv)));
  });
}
