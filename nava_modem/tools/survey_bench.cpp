// survey_bench: how well a survey from the robots' own packets (nava_survey) reads rooms that
// were measured. The survey's train (room packets with random data, SurveyTrain) is played
// through each measured response of a folder (every file and channel a room) with noise, and the
// survey's RT60 and DRR are held against the figures the response itself gives
// (measured_response.h: the definitions of ../shared/realrooms/README.md).
//
//   survey_bench --rir-dir DIR [--packets 10] [--snr-db 10] [--noise white|pink] [--gap 0.5]
//                [--seed 1] [--threads 2] [--regularisation 0.01] [--iterations 10]
//
// Prints one line per room and then
//   survey: K of N rooms within 10 % of their RT60 and 2 dB of their DRR (worst RT60 E %, ROOM; worst DRR D dB, ROOM)
// the figures of the survey's target (from 10 packets at SNR >= 10 dB). --regularisation and
// --iterations set the estimate's (SurveyOptions), to study it.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "measured_rooms.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/response_survey.h"
#include "nava_modem/room_channel.h"
#include "tool_args/parallel_for.h"
#include "tool_args/tool_args.h"

namespace {

using namespace nava_modem;
constexpr double kRate = 48000.0;
constexpr double kRt60Tolerance = 0.10;  // of the room's RT60
constexpr double kDrrToleranceDb = 2.0;

struct BenchArgs {
  std::string rir_dir;
  int packets = 10;
  double snr_db = 10.0;
  RoomOptions::Noise noise = RoomOptions::Noise::kWhite;
  double gap = 0.5;
  unsigned seed = 1;
  int threads = 2;
  SurveyOptions survey;  // --regularisation, --iterations: to study the estimate
  multirobot_audio::tools::ToolUsage usage;
};

BenchArgs Parse(int argc, char** argv) {
  const multirobot_audio::tools::ToolArgs args(
      "survey_bench",
      "survey_bench --rir-dir DIR [--packets 10] [--snr-db 10] [--noise white|pink] [--gap 0.5] [--seed 1] [--threads 2] "
      "[--regularisation 0.01] [--iterations 10]",
      multirobot_audio::tools::Words(argc, argv));
  BenchArgs a;
  a.usage = args.tool_usage();
  a.rir_dir = args.Required("--rir-dir");
  a.packets = static_cast<int>(args.Int("--packets", a.packets, 2, 1000));
  a.snr_db = args.Double("--snr-db", a.snr_db, -60.0, 100.0);
  const std::string noise = args.String("--noise", "white");
  if (noise == "pink") {
    a.noise = RoomOptions::Noise::kPink;
  } else if (noise != "white") {
    args.Fail("--noise: expected white or pink, got " + noise);
  }
  a.gap = args.Double("--gap", a.gap, 0.0, 10.0);
  a.seed = static_cast<unsigned>(args.Int("--seed", a.seed, 0, 1000000));
  a.threads = static_cast<int>(args.Int("--threads", a.threads, 0, 256));
  a.survey.regularisation = args.Double("--regularisation", a.survey.regularisation, 1e-9, 1e3);
  a.survey.iterations = static_cast<int>(args.Int("--iterations", a.survey.iterations, 0, 10000));
  if (!args.positional().empty()) args.Fail("unexpected " + args.positional()[0]);
  args.CheckAllUsed();
  return a;
}

struct Row {
  std::string name;
  ResponseMeasures truth, survey;
  std::size_t packets = 0, undecoded = 0;
  std::string error;  // why the survey gave no figures
  double rt60_error = 0.0, drr_error = 0.0;
  bool ok = false;
};

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool([&] {
    const BenchArgs a = Parse(argc, argv);
    const std::vector<tools::MeasuredRoom> rooms = tools::MeasuredRooms(a.rir_dir, a.usage);
    const std::vector<float> clean = SurveyTrain(kRate, a.packets, a.gap, a.seed);
    std::vector<Row> rows(rooms.size());
    multirobot_audio::tools::ParallelFor(rooms.size(), a.threads, [&](std::size_t i) {
      Row& row = rows[i];
      row.name = rooms[i].name;
      RoomOptions room;
      room.response = LoadImpulseResponse(rooms[i].path, rooms[i].channel, kRate);
      row.truth = MeasureResponse(room.response, kRate);
      room.noise = a.noise;
      room.snr_db = a.snr_db;
      room.seed = a.seed + static_cast<unsigned>(i);
      const std::vector<float> recording = RenderRoom(clean, kRate, room);
      try {
        const SurveyHeard heard = FindSurveyPackets(recording, kRate);
        row.packets = heard.packets.size();
        row.undecoded = heard.undecoded_s.size();
        const SurveyResult r = SurveyResponse(recording, kRate, heard, a.survey);
        row.survey = r.figures;
        if (const auto problem = ResponseProblem(r.figures)) row.error = *problem;
      } catch (const SurveyError& e) {
        row.error = e.what();
      }
      row.rt60_error = row.error.empty() ? row.survey.rt60_s / row.truth.rt60_s - 1.0 : NAN;
      row.drr_error = row.error.empty() ? row.survey.drr_db - row.truth.drr_db : NAN;
      row.ok = row.error.empty() && std::abs(row.rt60_error) <= kRt60Tolerance && std::abs(row.drr_error) <= kDrrToleranceDb;
    });
    std::printf("survey_bench: %d packets per room, %s noise at SNR %.1f dB, gaps drawn around %.2f s\n", a.packets,
                a.noise == RoomOptions::Noise::kPink ? "pink" : "white", a.snr_db, a.gap);
    std::printf("%-44s %8s %8s %8s %8s %7s %8s %8s\n", "room", "RT60 s", "survey", "DRR dB", "survey", "packets",
                "RT60 err", "DRR err");
    int ok = 0;
    const Row* worst_rt60 = nullptr;
    const Row* worst_drr = nullptr;
    for (const Row& row : rows) {
      ok += row.ok ? 1 : 0;
      if (!row.error.empty()) {
        std::printf("%-44s %8.3f %8s %8.2f %8s %4zu+%zu  no survey: %s\n", row.name.c_str(), row.truth.rt60_s, "-",
                    row.truth.drr_db, "-", row.packets, row.undecoded, row.error.c_str());
        continue;
      }
      std::printf("%-44s %8.3f %8.3f %8.2f %8.2f %4zu+%zu %+7.1f%% %+8.2f%s\n", row.name.c_str(), row.truth.rt60_s,
                  row.survey.rt60_s, row.truth.drr_db, row.survey.drr_db, row.packets, row.undecoded,
                  100.0 * row.rt60_error, row.drr_error, row.ok ? "" : "  (outside the target)");
      if (!worst_rt60 || std::abs(row.rt60_error) > std::abs(worst_rt60->rt60_error)) worst_rt60 = &row;
      if (!worst_drr || std::abs(row.drr_error) > std::abs(worst_drr->drr_error)) worst_drr = &row;
    }
    std::printf("survey: %d of %zu rooms within %.0f %% of their RT60 and %.0f dB of their DRR", ok, rows.size(),
                100.0 * kRt60Tolerance, kDrrToleranceDb);
    if (worst_rt60) {
      std::printf(" (worst RT60 %+.1f %%, %s; worst DRR %+.2f dB, %s)", 100.0 * worst_rt60->rt60_error,
                  worst_rt60->name.c_str(), worst_drr->drr_error, worst_drr->name.c_str());
    }
    std::printf("\n");
    return 0;
  });
}
