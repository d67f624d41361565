#include "model_calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/decode_table.h"
#include "measured_rooms.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/recorded_noise.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"
#include "parallel_cells.h"
#include "table_cells.h"

namespace audio_propagation::tools {
namespace {

struct Case {
  std::size_t room = 0;
  bool recorded = false;  // the recorded noise, else white
  double snr_db = 0.0;
  double predicted = 0.0, decoded = 0.0;
  int false_packets = 0;  // CRC passes with data never sent
};

struct Bin {
  double low, high;
  int cases = 0;
  double predicted = 0.0, decoded = 0.0;  // sums
};

}  // namespace

int CalibrateModel(const DecodeTableRequest& request) {
  const multirobot_audio::tools::ToolUsage& usage = request.usage;
  const std::string profile_name = nava_modem::ProfileName(request.profile);
  CellSetup setup;
  setup.profile = request.profile;
  setup.seed = request.seed;
  const double rate = setup.modem.sample_rate;
  DecodeTable table;
  try {
    table = LoadDecodeTable(request.table_file.empty() ? ShippedDecodeTable(profile_name) : request.table_file,
                            profile_name);
  } catch (const std::exception& e) {
    usage.Fail(e.what());
  }
  setup.table = table;
  setup.table.packets = request.packets;
  // What the measured rooms decode is judged in the steady state, whatever lead the table had.
  setup.table.lead_s = kTableLeadSeconds;
  const std::vector<nava_modem::tools::MeasuredRoom> rooms = nava_modem::tools::MeasuredRoomsIn(request.rir_dir, usage);
  std::vector<std::vector<float>> responses;
  for (const nava_modem::tools::MeasuredRoom& room : rooms) {
    if (const auto problem = nava_modem::ResponseProblem(room.figures)) usage.Fail(room.name + ": " + *problem);
    responses.push_back(nava_modem::LoadImpulseResponse(room.path, room.channel, rate));
  }
  // The recorded noise: heard as an interferer (the cells' speech kind) and weighed by the model
  // as white noise with its power where the receiver listens (RecordingWeight).
  std::optional<nava_modem::RecordingWeight> recording;
  if (!request.noise_file.empty()) {
    try {
      const nava_modem::Audio audio = nava_modem::ReadAudioFile(request.noise_file);
      recording.emplace(audio.samples, audio.sample_rate, request.profile, kTableSampleRate);
      setup.speech = nava_modem::ReadAudioAt(request.noise_file, rate);
    } catch (const std::exception& e) {
      usage.Fail("--noise-file " + request.noise_file + ": " + e.what());
    }
  }
  const std::vector<double> snrs =
      request.snr_db.empty() ? std::vector<double>{-15, -10, -5, 0, 5, 10, 15, 20} : request.snr_db;

  std::vector<Case> cases;
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    for (const bool recorded : {false, true}) {
      if (recorded && request.noise_file.empty()) continue;
      for (double snr : snrs) {
        Case c{r, recorded, snr};
        const std::vector<double> table_snrs =
            recorded ? recording->TableSnrsDb(snr + recording->in_band_offset_db()) : std::vector<double>{snr};
        c.predicted =
            PredictOutcome(table, Interference::kWhite, table_snrs, rooms[r].figures.drr_db, rooms[r].figures.rt60_s)
                .packet;
        cases.push_back(c);
      }
    }
  }
  std::fprintf(stderr, "decode_table_bench --calibrate: %zu rooms, %zu cases of %d packets on %d threads\n",
               rooms.size(), cases.size(), request.packets, request.threads);
  // A profile per thread, and the setup copied once per thread (the noise recording is long):
  // only the room changes from case to case.
  struct Worker {
    std::unique_ptr<nava_modem::ModemProfile> receiver;
    CellSetup setup;
  };
  ParallelCells(
      cases.size(), request.threads, [&] { return Worker{nava_modem::MakeProfile(setup.profile, setup.modem), setup}; },
      [&](Worker& w, std::size_t k) {
        w.setup.response = responses[cases[k].room];
        const Interference kind = cases[k].recorded ? Interference::kSpeech : Interference::kWhite;
        const CellCounts n = MeasureCell(w.setup, *w.receiver, k, kind, 0.0, 0.0, cases[k].snr_db);
        cases[k].decoded = static_cast<double>(n.heard[static_cast<int>(Heard::kPacket)]) / request.packets;
        cases[k].false_packets = n.false_packets;
      },
      [&](std::size_t done) {
        if (done % std::max<std::size_t>(1, cases.size() / 20) == 0) std::fprintf(stderr, "  %zu/%zu cases\n", done, cases.size());
      });

  std::printf("calibration of the %s model on %s: %d packets a case; noise white%s\n", profile_name.c_str(),
              request.rir_dir.c_str(), request.packets,
              request.noise_file.empty() ? "" : (" and " + request.noise_file).c_str());
  std::printf("%-44s %7s %6s %-9s %6s %9s %9s\n", "room", "drr_dB", "rt60_s", "noise", "snr_dB", "predicted", "decoded");
  std::vector<Bin> bins = {{0.0, 0.2}, {0.2, 0.6}, {0.6, 1.0001}};
  int false_packets = 0;
  std::string false_cases;  // where they were heard
  for (const Case& c : cases) {
    false_packets += c.false_packets;
    if (c.false_packets > 0) {
      char where[160];
      std::snprintf(where, sizeof where, "%s%s %s %+.0f dB: %d", false_cases.empty() ? "" : "; ",
                    rooms[c.room].name.c_str(), c.recorded ? "recorded" : "white", c.snr_db, c.false_packets);
      false_cases += where;
    }
    const nava_modem::tools::MeasuredRoom& room = rooms[c.room];
    std::printf("%-44s %+7.1f %6.2f %-9s %+6.0f %8.0f%% %8.0f%%\n", room.name.c_str(), room.figures.drr_db,
                room.figures.rt60_s, c.recorded ? "recorded" : "white", c.snr_db, 100.0 * c.predicted,
                100.0 * c.decoded);
    for (Bin& b : bins) {
      if (c.predicted >= b.low && c.predicted < b.high) {
        ++b.cases;
        b.predicted += c.predicted;
        b.decoded += c.decoded;
      }
    }
  }
  double worst = 0.0;
  for (const Bin& b : bins) {
    if (b.cases == 0) {
      std::printf("bin %3.0f-%3.0f %%: no case\n", 100.0 * b.low, std::min(100.0, 100.0 * b.high));
      continue;
    }
    const double predicted = 100.0 * b.predicted / b.cases, decoded = 100.0 * b.decoded / b.cases;
    worst = std::max(worst, std::fabs(predicted - decoded));
    std::printf("bin %3.0f-%3.0f %%: %4d cases, mean predicted %5.1f %%, mean decoded %5.1f %% (%+.1f points)\n",
                100.0 * b.low, std::min(100.0, 100.0 * b.high), b.cases, predicted, decoded, decoded - predicted);
  }
  // A wrong packet is one the receiver passes with data that was never sent (a CRC false accept).
  std::printf("false packets: %d of %zu packets sent%s\n", false_packets,
              cases.size() * static_cast<std::size_t>(request.packets),
              false_cases.empty() ? "" : (" (" + false_cases + ")").c_str());
  std::printf("calibration: worst bin %.1f points apart (the target: within 10)\n", worst);
  return 0;
}

}  // namespace audio_propagation::tools
