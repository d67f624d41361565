// nava_bench: how many packets the project's receivers (and minimodem, for the nava profile)
// decode from the same recordings.
//
//   nava_bench [--profile nava|room] [--packets 60] [--seed 1] [--snr-min -12] [--snr-max 0]
//              [--dir DIR] [--minimodem minimodem|none] [modem options]
//   nava_bench --rooms [--profile nava|room|both] [--packets 60] [--rooms-per-row 6] [--plot-packets 30]
//              [--plot FILE.png] [--seed 1] [--rate 48000] [--dir DIR] [--minimodem minimodem|none]
//              [--rir-dir DIR [--rir-packets 20] [--measured-only] [--drier DB,...]]
//
//   nava_bench --doa [--packets 100] [--plot FILE.png] [--seed 1] [--rate 48000]
//   nava_bench --arrival --rir-dir DIR [--packets 10] [--snr 10] [--min-drr -8] [--seed 1] [--rate 48000]
//   nava_bench --likeness --rir-dir DIR [--like-rooms 5] [--seed 1] [--rate 48000]
//   nava_bench --splice --early A.wav[:K] --late B.wav[:K] --at-ms T[,T...] --out DIR [--rate 48000]
//   nava_bench --link-cost [--seconds 120] [--period 6] [--runs 3] [--profile room|nava]
//   nava_bench --frames --rir-dir DIR [--bytes 64] [--speed all|R] [--count 20] [--snr 10] [--noise-file FILE]
//              [--threads 2] [--profile room|nava]
//   nava_bench --direction [--packets 40] [--min-decoded 10] [--max-packets 1000] [--snr 20] [--rt60 0.3,0.6,1,2] [--drr -15,-9,-3,3,9]
//              [--binaural-dir DIR] [--errors-out FILE.yaml] [--threads 2] [--profile room|nava]
//
// The decode tables of the simulated `acoustic` channel are measured with the same receivers by
// audio_propagation's decode_table_bench, where the tables live.
//
// Without --rooms: a WAV of N random packets for every full-band SNR (tone power over
// white-noise power across the whole band) from --snr-max down to --snr-min in 1 dB steps.
// With --rooms: the same packets through nava_room's renderer under each room condition of
// room_conditions.h (reverberation, speech, a motor whine, tilt, clock offset, an office, all at
// once), for each profile, the packets of a row spread over several rooms (seeds), and a PNG of delivery against the direct-to-reverberant ratio for
// RT60 0.3, 0.6 and 1.0 s; with --rir-dir, also rows through measured impulse responses (every
// channel of every audio file in DIR a room, its DRR and RT60 read in 600-5400 Hz), under white
// noise at 20 and 0 dB and speech at SIR 0 dB, with the targets for the nava receiver in measured
// rooms (--measured-only: those rows alone; --drier: each room also made drier to each DRR
// given above its own, DrierResponse, as homes and small rooms are). Either way each file is decoded by nava_decode (beside this program)
// and by minimodem as child processes, and the table gives the packets each decoded correctly,
// those decoded wrong (CRC-passing but never sent), and each decoder's CPU time; it ends with
// each decoder's speed (seconds of audio per CPU second) and the targets. With --doa: for each
// profile, a two-microphone pair and a four-microphone square, anechoic and in a reverberant
// room, N packets from random bearings at 2 m (nava_room's array renderer), decoded as the link
// does it (DecodeArray): the share of right front/back bits or the median and 90th-percentile
// bearing error, the estimator's CPU time against the decoding's, the targets, and a polar PNG.
// With --arrival: how well room packets are timed (their first arrival) through each measured
// room (arrival_table.h). With --likeness: each measured room's features beside the renderer's
// measured-like rooms at its RT60 and DRR (likeness_table.h). With --splice: two responses
// spliced at given times after their direct sounds, to decode through (splice_table.h). With
// --link-cost: what that timing adds to a link's CPU (link_cost.h). With --frames: frames of any
// length at each rate through each measured room (frame_table.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <tuple>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bench_support/child_process.h"
#include "bench_support/speech.h"
#include "modem_args.h"
#include "nava_bench_args.h"
#include "nava_bench_support.h"
#include "measured_rooms.h"
#include "arrival_table.h"
#include "direction_table.h"
#include "frame_table.h"
#include "likeness_table.h"
#include "splice_table.h"
#include "link_cost.h"
#include "nava_modem/array_decode.h"
#include "nava_modem/direction_estimator.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/room_array.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/wav_file.h"
#include "room_conditions.h"
#include "tool_args/line_chart.h"

namespace {

using namespace nava_modem;
using namespace nava_modem::tools;
using namespace bench_support;
using multirobot_audio::tools::LineChart;
using multirobot_audio::tools::LineSeries;
using multirobot_audio::tools::ToolUsage;
using multirobot_audio::tools::WriteLineChart;

struct Decoders {
  std::string nava_decode = SelfDir() + "/nava_decode";
  std::string minimodem;  // empty: not run
};

struct Decoded {
  Count count;
  double cpu_s = 0.0;
  bool ran = false;
};

Decoded DecodeWithProject(const Decoders& d, Profile profile, const ModemOptions& o, const std::string& file,
                          const std::vector<std::string>& sent) {
  std::vector<std::string> argv = {d.nava_decode, "--profile", ProfileName(profile), "--crc", CrcVariantName(o.crc)};
  if (profile == Profile::kNava) {
    for (const auto& [flag, value] : {std::pair<const char*, double>{"--mark", o.mark_hz}, {"--space", o.space_hz}, {"--baud", o.baud}}) {
      argv.push_back(flag);
      argv.push_back(std::to_string(value));
    }
  }
  argv.push_back(file);
  const RunResult r = Run(argv);
  if (r.status != 0) {
    std::cerr << "nava_bench: " << d.nava_decode << " failed on " << file << "\n";
    std::exit(1);
  }
  return {Score(NavaPackets(r.out), sent), r.cpu_s, true};
}

Decoded DecodeWithMinimodem(const Decoders& d, const ModemOptions& o, const std::string& file,
                            const std::vector<std::string>& sent) {
  if (d.minimodem.empty()) return {};
  const RunResult r = Run({d.minimodem, "--rx", "-q", "-f", file, "--mark", std::to_string(o.mark_hz), "--space",
                           std::to_string(o.space_hz), std::to_string(o.baud)});
  if (r.status < 0) {
    std::cerr << "nava_bench: could not run " << d.minimodem << " (use --minimodem none to skip it)\n";
    std::exit(1);
  }
  return {Score(MinimodemPackets(r.out, o.crc), sent), r.cpu_s, true};
}

int WhiteNoiseTable(const WhiteNoiseRequest& r, const ToolUsage& usage) {
  const int packets = r.packets;
  const unsigned seed = r.seed;
  const int snr_min = r.snr_min, snr_max = r.snr_max;
  const std::string dir = TempDir(usage, r.dir);
  Decoders decoders;
  decoders.minimodem = r.minimodem;
  const ToolModem& modem = r.modem;
  const ModemOptions& options = modem.options;

  std::mt19937 rng(seed);
  const auto profile = MakeProfile(modem.profile, options);
  const CleanSignal clean = RandomPackets(*profile, packets, 0.3, 0.0, rng);
  // The signal's power while it sounds: amplitude^2 / 2 for both profiles (one tone at a time).
  const double tone_power = options.amplitude * options.amplitude / 2.0;
  const bool with_minimodem = !decoders.minimodem.empty();
  std::printf("nava_bench: profile %s, %d packets, %.0f s of audio per file at %.0f Hz, files in %s\n",
              ProfileName(modem.profile), packets, clean.seconds, options.sample_rate, dir.c_str());
  std::printf("%8s %10s %10s %10s %10s %10s %10s\n", "snr_db", "ours", "ours_bad", "ours_cpu_s", "minimodem",
              "mm_bad", "mm_cpu_s");
  std::normal_distribution<double> gauss(0.0, 1.0);
  double ours_cpu = 0.0, mm_cpu = 0.0;
  int files = 0;
  std::map<int, Count> ours_at, mm_at;
  for (int snr = snr_max; snr >= snr_min; --snr) {
    const double sigma = std::sqrt(tone_power / std::pow(10.0, snr / 10.0));
    // Scale the mix so that the noise stays clear of full scale in a 16-bit file.
    const double scale = 0.9 / (4.0 * std::max(sigma, options.amplitude));
    std::vector<float> noisy(clean.samples.size());
    for (std::size_t k = 0; k < noisy.size(); ++k) noisy[k] = static_cast<float>(scale * (clean.samples[k] + sigma * gauss(rng)));
    const std::string file = dir + "/snr_" + std::to_string(snr) + ".wav";
    WriteWavFile(file, noisy, options.sample_rate);
    ++files;
    const Decoded ours = DecodeWithProject(decoders, modem.profile, options, file, clean.sent);
    const Decoded mm = DecodeWithMinimodem(decoders, options, file, clean.sent);
    ours_at[snr] = ours.count;
    ours_cpu += ours.cpu_s;
    if (mm.ran) mm_at[snr] = mm.count;
    mm_cpu += mm.cpu_s;
    if (mm.ran) {
      std::printf("%8d %10d %10d %10.3f %10d %10d %10.3f\n", snr, ours.count.right, ours.count.wrong, ours.cpu_s,
                  mm.count.right, mm.count.wrong, mm.cpu_s);
    } else {
      std::printf("%8d %10d %10d %10.3f %10s %10s %10s\n", snr, ours.count.right, ours.count.wrong, ours.cpu_s, "-", "-", "-");
    }
    std::fflush(stdout);
  }
  const double audio_total = clean.seconds * files;
  std::printf("speed: nava_decode %.0fx real time", audio_total / std::max(ours_cpu, 1e-9));
  if (with_minimodem) std::printf(", minimodem %.0fx real time", audio_total / std::max(mm_cpu, 1e-9));
  std::printf(" (seconds of audio per CPU second)\n");
  auto share = [&](int snr) { return ours_at.count(snr) ? 100.0 * ours_at[snr].right / packets : -1.0; };
  bool never_worse = true;
  for (const auto& [snr, m] : mm_at) never_worse = never_worse && ours_at[snr].right >= m.right;
  if (modem.profile != Profile::kNava) {
    // The room profile's targets are its room table's (nava_bench --rooms); here, where it breaks.
    int half = snr_max + 1;
    for (int snr = snr_max; snr >= snr_min && 2 * ours_at[snr].right >= packets; --snr) half = snr;
    std::printf("room: at least half the packets down to %d dB SNR; wrong packets: %d\n", half, [&] {
      int wrong = 0;
      for (const auto& [snr, c] : ours_at) wrong += c.wrong;
      return wrong;
    }());
    return 0;
  }
  std::printf("targets: -9 dB %.0f%% (>= 90), -10 dB %.0f%% (>= 50), never fewer than minimodem: %s, speed >= 500x: %s\n",
              share(-9), share(-10), with_minimodem ? (never_worse ? "yes" : "NO") : "not run",
              audio_total / std::max(ours_cpu, 1e-9) >= 500.0 ? "yes" : "NO");
  return 0;
}

struct RoomRow {
  Decoded nava, minimodem, room;
};

void MeasuredRoomsTable(const RoomsRequest& request, const ToolUsage& usage, const std::string& dir,
                        const std::vector<float>& speech);

int RoomsTable(const RoomsRequest& request, const ToolUsage& usage) {
  const int packets = request.packets, plot_packets = request.plot_packets, rooms_per_row = request.rooms_per_row;
  const unsigned seed = request.seed;
  const std::string dir = TempDir(usage, request.dir);
  const std::string plot = request.plot.empty() ? dir + "/delivery_vs_drr.png" : request.plot;
  const ModemOptions& options = request.options;
  const std::vector<Profile>& profiles = request.profiles;
  Decoders decoders;
  decoders.minimodem = request.minimodem;
  const bool has_nava = std::count(profiles.begin(), profiles.end(), Profile::kNava) > 0;
  const bool has_room = std::count(profiles.begin(), profiles.end(), Profile::kRoom) > 0;

  const std::vector<float> speech = ReadAudioAt(MakeSpeech(dir, seed), options.sample_rate);
  if (request.measured_only) {
    MeasuredRoomsTable(request, usage, dir, speech);
    return 0;
  }
  const std::vector<RoomCondition> conditions = RoomConditions();
  std::map<Profile, CleanSignal> clean;
  for (Profile p : profiles) {
    std::mt19937 rng(seed);
    clean[p] = RandomPackets(*MakeProfile(p, options), packets, 0.6, 0.4, rng);
  }
  // Renders `signal` under a condition and decodes it with the profile's decoders.
  double audio_s[3] = {0.0, 0.0, 0.0};  // nava, minimodem, room
  auto measure = [&](Profile p, const CleanSignal& signal, RoomOptions room, bool with_speech, const std::string& name,
                     RoomRow& row) {
    TiltOverBand(room, p == Profile::kNava, options);
    // The packets are spread over several rooms (seeds): one room's response at a few
    // frequencies (a random fade of each) decides much, and a row should not be one room's luck.
    std::vector<float> heard;
    const std::size_t packets_in = signal.ends.size();
    for (int k = 0; k < rooms_per_row; ++k) {
      const std::size_t first = k == 0 ? 0 : signal.ends[packets_in * k / rooms_per_row - 1];
      const std::size_t last = signal.ends[packets_in * (k + 1) / rooms_per_row - 1];
      const std::vector<float> part(signal.samples.begin() + static_cast<std::ptrdiff_t>(first),
                                    signal.samples.begin() + static_cast<std::ptrdiff_t>(last));
      RoomOptions this_room = room;
      this_room.seed = room.seed * 31u + static_cast<unsigned>(k);
      std::vector<float> talk;
      if (with_speech) {  // a different stretch of the speech for each room
        talk = SpeechFrom(speech, static_cast<std::size_t>(k) * 7919u * static_cast<std::size_t>(options.sample_rate / 10));
      }
      const std::vector<float> rendered = RenderRoom(part, options.sample_rate, this_room, talk);
      heard.insert(heard.end(), rendered.begin(), rendered.end());
    }
    const std::string file = dir + "/" + name + "_" + ProfileName(p) + ".wav";
    WriteWavFile(file, heard, options.sample_rate);
    const double seconds = heard.size() / options.sample_rate;
    if (p == Profile::kNava) {
      row.nava = DecodeWithProject(decoders, p, options, file, signal.sent);
      row.minimodem = DecodeWithMinimodem(decoders, options, file, signal.sent);
      audio_s[0] += seconds;
      if (row.minimodem.ran) audio_s[1] += seconds;
    } else {
      row.room = DecodeWithProject(decoders, p, options, file, signal.sent);
      audio_s[2] += seconds;
    }
  };

  std::printf("nava_bench --rooms: %d packets per row over %d rooms at %.0f Hz, files in %s\n", packets, rooms_per_row,
              options.sample_rate, dir.c_str());
  std::printf("%-26s %9s %5s %9s %5s %9s %5s\n", "condition", "nava", "bad", "minimodem", "bad", "room", "bad");
  auto cell = [&](const Decoded& d) {
    char text[32];
    if (!d.ran) return std::string("        -     -");
    std::snprintf(text, sizeof text, "%6d/%-2d %5d", d.count.right, packets, d.count.wrong);
    return std::string(text);
  };
  std::vector<RoomRow> rows;
  double cpu[3] = {0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    RoomRow row;
    RoomOptions room = conditions[k].room;
    room.seed = seed * 1000u + static_cast<unsigned>(k);
    for (Profile p : profiles) measure(p, clean[p], room, conditions[k].speech, "row" + std::to_string(k), row);
    std::printf("%-26s %s %s %s\n", conditions[k].name.c_str(), cell(row.nava).c_str(), cell(row.minimodem).c_str(),
                cell(row.room).c_str());
    std::fflush(stdout);
    cpu[0] += row.nava.cpu_s;
    cpu[1] += row.minimodem.cpu_s;
    cpu[2] += row.room.cpu_s;
    rows.push_back(row);
  }
  const char* names[3] = {"nava_decode --profile nava", "minimodem", "nava_decode --profile room"};
  std::printf("cpu:");
  for (int d = 0; d < 3; ++d) {
    if (audio_s[d] > 0.0) std::printf(" %s %.1f s (%.0fx real time);", names[d], cpu[d], audio_s[d] / std::max(cpu[d], 1e-9));
  }
  std::printf("\n");

  // Targets (issue "nava_modem in real rooms").
  const int need = (packets * 90 + 99) / 100;
  if (has_room) {
    int worst = packets, wrong = 0;
    for (const RoomRow& r : rows) {
      worst = std::min(worst, r.room.count.right);
      wrong += r.room.count.wrong;
    }
    std::printf("targets room: every row >= 90%% (worst %d/%d): %s; wrong packets 0 (%d): %s; >= 50x real time: %s\n", worst,
                packets, worst >= need ? "yes" : "NO", wrong, wrong == 0 ? "yes" : "NO",
                audio_s[2] / std::max(cpu[2], 1e-9) >= 50.0 ? "yes" : "NO");
  }
  if (has_nava) {
    bool tilt_clock = true, never_fewer = true;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const std::string& n = conditions[k].name;
      if (n.rfind("tilt", 0) == 0 || n.rfind("clock", 0) == 0) tilt_clock = tilt_clock && rows[k].nava.count.right >= need;
      if (rows[k].minimodem.ran) never_fewer = never_fewer && rows[k].nava.count.right >= rows[k].minimodem.count.right;
    }
    std::printf("targets nava: tilt and clock rows >= 90%%: %s; never fewer than minimodem: %s; rt60 0.3 drr +3 >= 50%% (%d/%d): %s\n",
                tilt_clock ? "yes" : "NO", decoders.minimodem.empty() ? "not run" : (never_fewer ? "yes" : "NO"),
                rows[0].nava.count.right, packets, 2 * rows[0].nava.count.right >= packets ? "yes" : "NO");
  }

  if (!request.rir_dir.empty()) MeasuredRoomsTable(request, usage, dir, speech);

  if (plot_packets == 0) return 0;
  // Delivery against DRR for each reverberation time of the curve.
  LineChart chart;
  chart.title = "Packets decoded against direct-to-reverberant ratio";
  chart.x_label = "DRR (dB)";
  chart.y_label = "decoded (%)";
  std::printf("delivery against DRR (%d packets per point, %s rooms, white noise SNR %g dB):\n%-8s %-6s", plot_packets,
              RoomModelName(request.curve_model), request.curve_snr_db, "rt60 s", "drr dB");
  std::printf("%10s%10s%10s\n", has_nava ? "nava" : "", has_nava && !decoders.minimodem.empty() ? "minimodem" : "", has_room ? "room" : "");
  const std::vector<double>& rt60s = request.curve_rt60;
  for (int r = 0; r < static_cast<int>(rt60s.size()); ++r) {
    // The same packets at every reverberation time, each sent once the last one's reverberation
    // has fallen by 60 dB (at least 0.6 s after it, as the table's rows), as a sender that
    // waits for quiet air would: the curve is about one packet in a room, not about a tail
    // running into the next packet.
    std::map<Profile, CleanSignal> few;
    for (Profile p : profiles) {
      std::mt19937 rng(seed + 1);
      few[p] = RandomPackets(*MakeProfile(p, options), plot_packets, std::max(0.6, rt60s[r]), 0.4, rng);
    }
    LineSeries series[3];
    for (int d = 0; d < 3; ++d) {
      series[d].colour = r;
      series[d].style = d == 2 ? LineSeries::Style::kSolid : d == 0 ? LineSeries::Style::kDashed : LineSeries::Style::kDotted;
      char label[64];
      std::snprintf(label, sizeof label, "%s, rt60 %g s", d == 0 ? "nava" : d == 1 ? "minimodem" : "room", rt60s[r]);
      series[d].label = label;
    }
    for (int drr = 12; drr >= request.curve_drr_min; drr -= 3) {
      RoomOptions room;
      room.rt60 = rt60s[r];
      room.drr_db = drr;
      room.model = request.curve_model;
      room.noise = RoomOptions::Noise::kWhite;
      room.snr_db = request.curve_snr_db;
      room.seed = seed * 7919u + static_cast<unsigned>(r * 100 + drr + 50);
      RoomRow row;
      char name[64];
      std::snprintf(name, sizeof name, "rt60_%g_drr_%d", rt60s[r], drr);
      for (Profile p : profiles) measure(p, few[p], room, false, name, row);
      const Decoded* ds[3] = {&row.nava, &row.minimodem, &row.room};
      std::printf("%-8g %-6d", rt60s[r], drr);
      for (int d = 0; d < 3; ++d) {
        if (!ds[d]->ran) {
          std::printf("%10s", "");
          continue;
        }
        series[d].x.push_back(drr);
        series[d].y.push_back(100.0 * ds[d]->count.right / plot_packets);
        std::printf("%9.0f%%", 100.0 * ds[d]->count.right / plot_packets);
      }
      std::printf("\n");
      std::fflush(stdout);
    }
    for (int d = 0; d < 3; ++d) {
      if (!series[d].x.empty()) chart.series.push_back(series[d]);
    }
  }
  try {
    WriteLineChart(plot, chart);
  } catch (const std::exception& e) {
    std::cerr << "nava_bench: " << e.what() << "\n";
    return 1;
  }
  std::printf("plot: %s\n", plot.c_str());
  return 0;
}


// The conditions every measured room is heard under: white noise at full-band SNR 20 and 0 dB,
// and speech at SIR 0 dB over the 20 dB noise.
std::vector<RoomCondition> MeasuredConditions() {
  std::vector<RoomCondition> conditions;
  for (const double snr : {20.0, 0.0}) {
    RoomCondition c{snr == 20.0 ? "white 20 dB" : "white 0 dB", {}, false};
    c.room.noise = RoomOptions::Noise::kWhite;
    c.room.snr_db = snr;
    conditions.push_back(c);
  }
  RoomCondition speech{"speech 0 dB", {}, true};
  speech.room.noise = RoomOptions::Noise::kWhite;
  speech.room.snr_db = 20.0;
  speech.room.sir_db = 0.0;
  conditions.push_back(speech);
  return conditions;
}

// The packets through every measured room of request.rir_dir under MeasuredConditions, each
// decoded by the profiles' decoders (and minimodem), a line per room and condition, then the
// targets of the issue on the thesis's FSK in measured rooms.
void MeasuredRoomsTable(const RoomsRequest& request, const ToolUsage& usage, const std::string& dir,
                        const std::vector<float>& speech) {
  const ModemOptions& options = request.options;
  const int packets = request.rir_packets;
  Decoders decoders;
  decoders.minimodem = request.minimodem;
  const std::vector<MeasuredRoom> rooms = MeasuredRooms(request.rir_dir, usage);
  const std::vector<RoomCondition> conditions = MeasuredConditions();
  std::map<Profile, CleanSignal> clean;
  for (Profile p : request.profiles) {
    std::mt19937 rng(request.seed + 7);
    clean[p] = RandomPackets(*MakeProfile(p, options), packets, 0.6, 0.4, rng);
  }
  std::printf("measured rooms (%s): %d packets per room and condition at %.0f Hz; DRR and RT60 in 600-5400 Hz\n",
              request.rir_dir.c_str(), packets, options.sample_rate);
  std::printf("%-44s %7s %6s %-12s %9s %5s %9s %5s %9s %5s\n", "room", "drr_dB", "rt60_s", "condition", "nava", "bad",
              "minimodem", "bad", "room", "bad");
  auto cell = [&](const Decoded& d) {
    char text[32];
    if (!d.ran) return std::string("        -     -");
    std::snprintf(text, sizeof text, "%6d/%-2d %5d", d.count.right, packets, d.count.wrong);
    return std::string(text);
  };
  // Per DRR class (>= +3, 0..+3, below 0): the worst condition's nava packets, in each room.
  int worst_high = packets, worst_mid_pooled = 3 * packets, high_rooms = 0, mid_rooms = 0;
  bool never_fewer = true;
  int wrong[3] = {0, 0, 0}, right[3] = {0, 0, 0}, total[3] = {0, 0, 0};
  // Each measured room as measured, then made drier to each of request.drier above its own DRR
  // (DrierResponse); a drier version draws its noise as a room of its own after the measured ones.
  std::size_t variant = rooms.size();
  for (std::size_t m = 0; m < rooms.size(); ++m) {
    const std::vector<float> measured = LoadImpulseResponse(rooms[m].path, rooms[m].channel, options.sample_rate);
    std::vector<std::tuple<std::size_t, std::string, std::vector<float>>> versions = {{m, rooms[m].name, measured}};
    // The room's own DRR at the rate the packets are rendered at (the list's is at the file's).
    const double own_drr = request.drier.empty() ? 0.0 : MeasureResponse(measured, options.sample_rate).drr_db;
    for (double d : request.drier) {
      if (d <= own_drr) continue;
      char name[64];
      std::snprintf(name, sizeof name, " drier %+.0f dB", d);
      try {
        versions.emplace_back(variant++, rooms[m].name + name, DrierResponse(measured, options.sample_rate, d));
      } catch (const std::exception& e) {
        usage.Fail("--drier: " + rooms[m].name + ": " + e.what());
      }
    }
    for (const auto& [r, room_name, response] : versions) {
      const ResponseMeasures figures = r == m ? rooms[m].figures : MeasureResponse(response, options.sample_rate);
      const double drr = figures.drr_db;
      int worst = packets, pooled = 0;
      for (std::size_t k = 0; k < conditions.size(); ++k) {
        RoomRow row;
        for (Profile p : request.profiles) {
          RoomOptions o = conditions[k].room;
          o.response = response;
          o.seed = request.seed * 7919u + static_cast<unsigned>(r * 10 + k);
          std::vector<float> talk;
          if (conditions[k].speech) talk = SpeechFrom(speech, (r * 3 + k) * 7919u * static_cast<std::size_t>(options.sample_rate / 10));
          const std::vector<float> heard = RenderRoom(clean[p].samples, options.sample_rate, o, talk);
          const std::string file = dir + "/measured_" + std::to_string(r) + "_" + std::to_string(k) + "_" + ProfileName(p) + ".wav";
          WriteWavFile(file, heard, options.sample_rate);
          if (p == Profile::kNava) {
            row.nava = DecodeWithProject(decoders, p, options, file, clean[p].sent);
            row.minimodem = DecodeWithMinimodem(decoders, options, file, clean[p].sent);
          } else {
            row.room = DecodeWithProject(decoders, p, options, file, clean[p].sent);
          }
        }
        const Decoded* ds[3] = {&row.nava, &row.minimodem, &row.room};
        for (int d = 0; d < 3; ++d) {
          if (!ds[d]->ran) continue;
          right[d] += ds[d]->count.right;
          wrong[d] += ds[d]->count.wrong;
          total[d] += packets;
        }
        if (row.nava.ran) {
          worst = std::min(worst, row.nava.count.right);
          pooled += row.nava.count.right;
          if (row.minimodem.ran) never_fewer = never_fewer && row.nava.count.right >= row.minimodem.count.right;
        }
        std::printf("%-44s %+7.1f %6.2f %-12s %s %s %s\n", room_name.c_str(), drr, figures.rt60_s,
                    conditions[k].name.c_str(), cell(row.nava).c_str(), cell(row.minimodem).c_str(), cell(row.room).c_str());
        std::fflush(stdout);
      }
      if (drr >= 3.0) {
        ++high_rooms;
        worst_high = std::min(worst_high, worst);
      } else if (drr >= 0.0) {
        ++mid_rooms;
        worst_mid_pooled = std::min(worst_mid_pooled, pooled);
      }
    }
  }
  const char* names[3] = {"nava", "minimodem", "room"};
  std::printf("measured totals:");
  for (int d = 0; d < 3; ++d) {
    if (total[d] > 0) std::printf(" %s %d/%d (%.1f%%, %d wrong);", names[d], right[d], total[d], 100.0 * right[d] / total[d], wrong[d]);
  }
  std::printf("\n");
  if (!clean.count(Profile::kNava)) return;
  auto verdict = [](int rooms, bool ok) { return rooms == 0 ? "no such room" : ok ? "yes" : "NO"; };
  const int need_high = (packets * 95 + 99) / 100, need_mid = (3 * packets * 70 + 99) / 100;
  std::printf("targets measured nava: DRR >= +3 dB >= 95%% in every condition (%d rooms, worst %d/%d): %s; "
              "DRR 0..+3 dB >= 70%% over the conditions (%d rooms, worst %d/%d): %s; never fewer than minimodem: %s; "
              "wrong packets 0 (%d): %s\n",
              high_rooms, high_rooms ? worst_high : 0, packets, verdict(high_rooms, worst_high >= need_high), mid_rooms,
              mid_rooms ? worst_mid_pooled : 0, 3 * packets, verdict(mid_rooms, worst_mid_pooled >= need_mid),
              decoders.minimodem.empty() ? "not run" : (never_fewer ? "yes" : "NO"), wrong[0], wrong[0] == 0 ? "yes" : "NO");
}


// Where each profile's receptions come from, as a microphone array on a robot would tell it.
struct Geometry {
  const char* name;
  std::vector<Microphone2D> mics;
  bool pair;  // two microphones: a front/back bit
};
struct DoaCondition {
  const char* name;
  RoomOptions room;
};
struct DoaResult {
  int packets = 0, decoded = 0, eligible = 0, bit_right = 0, unresolved = 0;
  std::vector<double> errors_deg;  // full bearings: |error| per decoded packet (180 when NaN)
  std::vector<std::pair<double, double>> truth_and_estimate;  // rad, for the polar plot
  double decode_cpu = 0.0, estimate_cpu = 0.0;
};

DoaResult MeasureDoa(Profile p, const ModemOptions& options, const Geometry& g, const DoaCondition& c, int packets,
                     unsigned seed) {
  const auto profile = MakeProfile(p, options);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> bearing(-M_PI, M_PI);
  std::uniform_int_distribution<int> byte(0, 255);
  const double rate = options.sample_rate;
  DoaResult r;
  for (int k = 0; k < packets; ++k) {
    std::vector<std::uint8_t> data(kDataBytes);
    for (auto& b : data) b = static_cast<std::uint8_t>(byte(rng));
    const std::vector<float> clean = PacketInSilence(*profile, data, 0.4, 0.4);
    ArraySource source;
    source.mics = g.mics;
    source.bearing = bearing(rng);
    source.distance = 2.0;
    RoomOptions room = c.room;
    room.seed = seed * 1000u + static_cast<unsigned>(k);
    const std::vector<std::vector<float>> heard = RenderRoomArray(clean, rate, room, source);
    double estimate_cpu = 0.0;
    const double started = CpuNow();
    const std::vector<RxEvent> events = DecodeArray(*profile, {}, heard, g.mics, &estimate_cpu);
    r.decode_cpu += CpuNow() - started - estimate_cpu;
    r.estimate_cpu += estimate_cpu;
    ++r.packets;
    const auto it = std::find_if(events.begin(), events.end(),
                                 [&](const RxEvent& e) { return e.kind == RxEvent::Kind::kPacket && e.data == data; });
    if (it == events.end()) continue;
    ++r.decoded;
    const double truth = source.bearing, estimate = it->direction;
    r.truth_and_estimate.emplace_back(truth, estimate);
    if (!std::isfinite(estimate)) ++r.unresolved;
    if (g.pair) {
      // The bit is judged where a pair can tell: more than 20 degrees off its broadside.
      if (std::abs(std::cos(truth)) <= std::sin(20.0 * M_PI / 180.0)) continue;
      ++r.eligible;
      r.bit_right += SameEndOfAxis(truth, estimate);
    } else {
      const double error = std::isfinite(estimate) ? std::abs(std::remainder(estimate - truth, 2.0 * M_PI)) * 180.0 / M_PI : 180.0;
      r.errors_deg.push_back(error);
    }
  }
  return r;
}

// A polar panel per measurement: each packet a line from its true bearing (on the outer
// circle) to the estimated one (on the inner); a NaN estimate is a short red tick.
void WritePolarPlot(const std::string& path, const std::vector<std::string>& titles, const std::vector<DoaResult>& results) {
  const int panel = 330, columns = 4;
  const int rows = static_cast<int>((results.size() + columns - 1) / columns);
  cv::Mat image(rows * panel, columns * panel, CV_8UC3, cv::Scalar(255, 255, 255));
  for (std::size_t k = 0; k < results.size(); ++k) {
    const cv::Point2d centre((k % columns) * panel + panel / 2.0, (k / columns) * panel + panel / 2.0 + 10.0);
    const double outer = panel * 0.38, inner = panel * 0.28;
    cv::circle(image, centre, static_cast<int>(outer), cv::Scalar(200, 200, 200), 1, cv::LINE_AA);
    cv::circle(image, centre, static_cast<int>(inner), cv::Scalar(225, 225, 225), 1, cv::LINE_AA);
    cv::line(image, centre, centre + cv::Point2d(outer + 8, 0), cv::Scalar(160, 160, 160), 1);  // the robot's +x
    auto at = [&](double angle, double radius) { return centre + cv::Point2d(radius * std::cos(angle), -radius * std::sin(angle)); };
    for (const auto& [truth, estimate] : results[k].truth_and_estimate) {
      if (!std::isfinite(estimate)) {
        cv::line(image, at(truth, outer), at(truth, outer - 8), cv::Scalar(40, 40, 220), 2, cv::LINE_AA);
        continue;
      }
      cv::line(image, at(truth, outer), at(estimate, inner), cv::Scalar(180, 119, 31), 1, cv::LINE_AA);
    }
    cv::putText(image, titles[k], cv::Point(static_cast<int>(centre.x) - panel / 2 + 8, static_cast<int>(centre.y) - panel / 2 + 8),
                cv::FONT_HERSHEY_SIMPLEX, 0.42, cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
  }
  if (!cv::imwrite(path, image)) throw std::runtime_error(path + ": cannot write the PNG");
}

int DoaTable(const DoaRequest& request, const ToolUsage& usage) {
  const int packets = request.packets;
  const unsigned seed = request.seed;
  const std::string dir = TempDir(usage, request.dir);
  const std::string plot = request.plot.empty() ? dir + "/doa_polar.png" : request.plot;
  const ModemOptions& options = request.options;
  const double half = 0.1 / std::sqrt(2.0);
  const std::vector<Geometry> geometries = {
      {"pair 0.2 m on x", {{0.1, 0.0}, {-0.1, 0.0}}, true},
      {"square 0.1 m", {{half, half}, {-half, half}, {-half, -half}, {half, -half}}, false}};
  DoaCondition anechoic{"anechoic", {}};
  anechoic.room.noise = RoomOptions::Noise::kWhite;
  anechoic.room.snr_db = 10.0;
  DoaCondition room{"rt60 0.5 s drr 0 dB", anechoic.room};
  room.room.rt60 = 0.5;
  room.room.drr_db = 0.0;
  std::printf("nava_bench --doa: %d packets per line from random bearings at 2 m, SNR 10 dB, %.0f Hz\n", packets,
              options.sample_rate);
  std::printf("%-8s %-16s %-22s %8s %12s %10s %10s %10s %9s\n", "profile", "geometry", "condition", "decoded", "front/back",
              "median_deg", "p90_deg", "no_dir", "cpu_est");
  std::vector<std::string> titles;
  std::vector<DoaResult> results;
  bool pair_anechoic = true, pair_room = true, square_anechoic = true, square_room = true;
  for (Profile p : {Profile::kNava, Profile::kRoom}) {
    for (const Geometry& g : geometries) {
      for (const DoaCondition* c : {&anechoic, &room}) {
        DoaResult r = MeasureDoa(p, options, g, *c, packets, seed);
        const double share = r.eligible ? 100.0 * r.bit_right / r.eligible : 0.0;
        const double median = Percentile(r.errors_deg, 0.5), p90 = Percentile(r.errors_deg, 0.9);
        char bits[32] = "-", med[32] = "-", ninety[32] = "-";
        if (g.pair) std::snprintf(bits, sizeof bits, "%.1f%% of %d", share, r.eligible);
        if (!g.pair) {
          std::snprintf(med, sizeof med, "%.1f", median);
          std::snprintf(ninety, sizeof ninety, "%.1f", p90);
        }
        std::printf("%-8s %-16s %-22s %5d/%-3d %12s %10s %10s %10d %8.1f%%\n", ProfileName(p), g.name, c->name, r.decoded,
                    r.packets, bits, med, ninety, r.unresolved, 100.0 * r.estimate_cpu / std::max(1e-9, r.decode_cpu));
        std::fflush(stdout);
        const bool reverberant = c == &room;
        if (g.pair && !reverberant) pair_anechoic = pair_anechoic && share >= 97.0;
        if (g.pair && reverberant && p == Profile::kRoom) pair_room = share >= 90.0;
        if (!g.pair && p == Profile::kRoom) {
          if (reverberant) {
            square_room = median <= 10.0 && p90 <= 25.0;
          } else {
            square_anechoic = median <= 3.0;
          }
        }
        titles.push_back(std::string(ProfileName(p)) + ", " + g.name + ", " + c->name);
        results.push_back(r);
      }
    }
  }
  double decode = 0.0, estimate = 0.0;
  for (const DoaResult& r : results) {
    decode += r.decode_cpu;
    estimate += r.estimate_cpu;
  }
  std::printf("targets: pair anechoic >= 97%% (both profiles): %s; pair rt60 0.5 drr 0 >= 90%% (room): %s; "
              "square anechoic median <= 3 deg (room): %s; square rt60 0.5 drr 0 median <= 10, p90 <= 25 deg (room): %s; "
              "estimation <= 10%% of decoding CPU (%.1f%%): %s\n",
              pair_anechoic ? "yes" : "NO", pair_room ? "yes" : "NO", square_anechoic ? "yes" : "NO", square_room ? "yes" : "NO",
              100.0 * estimate / std::max(1e-9, decode), estimate <= 0.1 * decode ? "yes" : "NO");
  try {
    WritePolarPlot(plot, titles, results);
  } catch (const std::exception& e) {
    std::cerr << "nava_bench: " << e.what() << "\n";
    return 1;
  }
  std::printf("plot: %s\n", plot.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool([&] {
    const NavaBenchOptions o = ParseNavaBenchArgs(multirobot_audio::tools::Words(argc, argv));
    switch (o.mode) {
      case NavaBenchOptions::Mode::kDoa:
        return DoaTable(o.doa, o.usage);
      case NavaBenchOptions::Mode::kArrival:
        return ArrivalTable(o.arrival, o.usage);
      case NavaBenchOptions::Mode::kLikeness:
        return LikenessTable(o.likeness, o.usage);
      case NavaBenchOptions::Mode::kSplice:
        return SpliceTable(o.splice, o.usage);
      case NavaBenchOptions::Mode::kLinkCost:
        return LinkCostTable(o.link_cost);
      case NavaBenchOptions::Mode::kFrames:
        return FrameTable(o.frames, o.usage);
      case NavaBenchOptions::Mode::kDirection:
        return DirectionTable(o.direction, o.usage);
      case NavaBenchOptions::Mode::kRooms:
        return RoomsTable(o.rooms, o.usage);
      case NavaBenchOptions::Mode::kWhiteNoise:
        break;
    }
    return WhiteNoiseTable(o.white, o.usage);
  });
}
