#include "frame_table.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "measured_rooms.h"
#include "nava_bench_support.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/room_channel.h"
#include "nava_modem/room_frame.h"
#include "tool_args/parallel_for.h"

namespace nava_modem::tools {
namespace {

// The bar for a room-ear: 19 frames in 20.
constexpr double kDelivered = 0.95;
// Its targets: the fastest rate carries at least 250 bit/s and delivers in three quarters of the
// room-ears under both conditions; some rate of at least 100 bit/s delivers in every room-ear
// under white noise; every rate decodes at 50 times real time or more.
constexpr double kFastBitRate = 250.0, kEveryRoomBitRate = 100.0, kRealTimes = 50.0;

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Frames of random data, each after a gap of 0.6 s plus up to 0.4 s, and what they carry.
struct FrameTrain {
  std::vector<float> samples;
  std::vector<std::vector<std::uint8_t>> sent;
};
FrameTrain RandomFrames(const ModemProfile& profile, int frames, int bytes, int rate, std::mt19937& rng) {
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_real_distribution<double> gap(0.6, 1.0);
  const double fs = profile.options().sample_rate;
  FrameTrain t;
  for (int f = 0; f < frames; ++f) {
    t.samples.insert(t.samples.end(), static_cast<std::size_t>(gap(rng) * fs), 0.0f);
    std::vector<std::uint8_t> data(static_cast<std::size_t>(bytes));
    for (auto& b : data) b = static_cast<std::uint8_t>(byte(rng));
    const std::vector<float> sound = profile.Modulate(data, rate);
    t.samples.insert(t.samples.end(), sound.begin(), sound.end());
    t.sent.push_back(std::move(data));
  }
  t.samples.insert(t.samples.end(), static_cast<std::size_t>(1.0 * fs), 0.0f);
  return t;
}

struct Cell {
  int right = 0, wrong = 0;
  double audio_s = 0.0, cpu_s = 0.0;
  std::vector<std::string> wrong_frames;  // each wrong frame: when, its data, how far from the nearest sent
};

// The train through one room under one condition, decoded: frames right (each sent frame once)
// and wrong (passing the CRC, never sent).
Cell Decode(const ModemProfile& profile, const FrameTrain& train, const RoomOptions& room, const std::vector<float>& interferer) {
  const std::vector<float> heard = RenderRoom(train.samples, profile.options().sample_rate, room, interferer);
  Cell cell;
  cell.audio_s = static_cast<double>(heard.size()) / profile.options().sample_rate;
  const double start = ThreadCpuSeconds();
  std::vector<RxEvent> events;
  const auto receiver = profile.MakeReceiver(ReceiverOptions{});
  receiver->Process(heard.data(), heard.size(), events);
  receiver->Flush(events);
  cell.cpu_s = ThreadCpuSeconds() - start;
  std::vector<bool> matched(train.sent.size(), false);
  for (const RxEvent& e : events) {
    if (e.kind != RxEvent::Kind::kPacket) continue;
    bool found = false;
    for (std::size_t k = 0; k < train.sent.size() && !found; ++k) {
      if (!matched[k] && train.sent[k] == e.data) matched[k] = found = true;
    }
    if (found) {
      ++cell.right;
      continue;
    }
    ++cell.wrong;
    // The sent frame nearest to it, in bits (a frame decoded twice is 0 bits from one).
    int nearest = 1 << 30;
    for (const auto& sent : train.sent) {
      if (sent.size() != e.data.size()) continue;
      int bits = 0;
      for (std::size_t k = 0; k < sent.size(); ++k) bits += __builtin_popcount(static_cast<unsigned>(sent[k] ^ e.data[k]));
      nearest = std::min(nearest, bits);
    }
    char text[160];
    std::snprintf(text, sizeof text, "at %.2f-%.2f s, %zu bytes at rate %d, %s from the nearest sent", e.start, e.end, e.data.size(),
                  e.rate, nearest == (1 << 30) ? "no frame that long" : (std::to_string(nearest) + " bits").c_str());
    cell.wrong_frames.push_back(text);
  }
  return cell;
}

std::string RateLabel(const ModemProfile& profile, int rate) {
  return profile.profile() == Profile::kNava ? std::string("nava") : std::string(room_frame::RateName(rate));
}

}  // namespace

int FrameTable(const FramesRequest& request, const multirobot_audio::tools::ToolUsage& usage) {
  const ModemOptions& options = request.options;
  const double fs = options.sample_rate;
  const std::unique_ptr<ModemProfile> profile = MakeProfile(request.profile, options);
  std::vector<int> speeds = request.speeds;
  if (speeds.empty()) {
    for (int r = 0; r < profile->Format().rates; ++r) speeds.push_back(r);
  }
  const std::vector<MeasuredRoom> rooms = MeasuredRooms(request.rir_dir, usage);
  std::vector<float> recording;
  if (!request.noise_file.empty()) {
    try {
      recording = ReadAudioAt(request.noise_file, fs);
    } catch (const std::exception& e) {
      usage.Fail("--noise-file " + request.noise_file + ": " + e.what());
    }
  }
  std::vector<std::string> conditions = {"white"};
  if (!recording.empty()) conditions.push_back("recording");

  std::map<int, FrameTrain> trains;
  for (int rate : speeds) {
    std::mt19937 rng(request.seed * 1000u + static_cast<unsigned>(rate));
    trains[rate] = RandomFrames(*profile, request.frames, request.bytes, rate, rng);
  }
  // cells[room][condition][speed index]
  std::vector<std::vector<std::vector<Cell>>> cells(
      rooms.size(), std::vector<std::vector<Cell>>(conditions.size(), std::vector<Cell>(speeds.size())));
  multirobot_audio::tools::ParallelFor(rooms.size() * conditions.size() * speeds.size(), request.threads, [&](std::size_t i) {
    const std::size_t s = i % speeds.size(), c = (i / speeds.size()) % conditions.size(), m = i / speeds.size() / conditions.size();
    RoomOptions room;
    room.response = LoadImpulseResponse(rooms[m].path, rooms[m].channel, fs);
    room.seed = request.seed + 17 + static_cast<unsigned>(m);
    if (conditions[c] == "white") {
      room.noise = RoomOptions::Noise::kWhite;
      room.snr_db = request.snr_db;
      cells[m][c][s] = Decode(*profile, trains[speeds[s]], room, {});
    } else {
      room.sir_db = request.snr_db;
      cells[m][c][s] = Decode(*profile, trains[speeds[s]], room, recording);
    }
  });

  std::printf("frames (%s): %d frames of %d bytes per room-ear, condition and rate, %s profile at %.0f Hz; "
              "white noise%s at full-band SNR %.0f dB\n",
              request.rir_dir.c_str(), request.frames, request.bytes, ProfileName(request.profile), fs,
              recording.empty() ? "" : (" and " + request.noise_file).c_str(), request.snr_db);
  std::printf("%-44s %7s %6s", "room", "drr_dB", "rt60_s");
  for (const std::string& c : conditions) {
    for (int rate : speeds) std::printf(" %14s", (c.substr(0, 5) + ":" + RateLabel(*profile, rate)).c_str());
  }
  std::printf("\n");
  const int bar = static_cast<int>(std::ceil(kDelivered * request.frames - 1e-9));
  for (std::size_t m = 0; m < rooms.size(); ++m) {
    std::printf("%-44s %+7.1f %6.2f", rooms[m].name.c_str(), rooms[m].figures.drr_db, rooms[m].figures.rt60_s);
    for (std::size_t c = 0; c < conditions.size(); ++c) {
      for (std::size_t s = 0; s < speeds.size(); ++s) {
        const Cell& cell = cells[m][c][s];
        char text[32];
        std::snprintf(text, sizeof text, "%d/%d%s%s", cell.right, request.frames, cell.right >= bar ? " " : "*",
                      cell.wrong ? (" w" + std::to_string(cell.wrong)).c_str() : "");
        std::printf(" %14s", text);
      }
    }
    std::printf("\n");
  }
  std::printf("(* below %d of %d)\n", bar, request.frames);
  for (std::size_t m = 0; m < rooms.size(); ++m) {
    for (std::size_t c = 0; c < conditions.size(); ++c) {
      for (std::size_t s = 0; s < speeds.size(); ++s) {
        for (const std::string& w : cells[m][c][s].wrong_frames) {
          std::printf("wrong frame: %s, %s, rate %d: %s\n", rooms[m].name.c_str(), conditions[c].c_str(), speeds[s], w.c_str());
        }
      }
    }
  }
  bool fast_met = false, every_met = false, speed_met = true, none_wrong = true;
  double fastest = 0.0;
  for (std::size_t s = 0; s < speeds.size(); ++s) {
    const int rate = speeds[s];
    const double bit_rate = 8.0 * request.bytes / profile->Airtime(static_cast<std::size_t>(request.bytes), rate);
    fastest = std::max(fastest, bit_rate);
    bool all_conditions_three_quarters = true;
    double audio = 0.0, cpu = 0.0;
    for (std::size_t c = 0; c < conditions.size(); ++c) {
      int good = 0, right = 0, wrong = 0;
      for (std::size_t m = 0; m < rooms.size(); ++m) {
        const Cell& cell = cells[m][c][s];
        good += cell.right >= bar;
        right += cell.right;
        wrong += cell.wrong;
        audio += cell.audio_s;
        cpu += cell.cpu_s;
      }
      none_wrong = none_wrong && wrong == 0;
      all_conditions_three_quarters = all_conditions_three_quarters && 4 * good >= 3 * static_cast<int>(rooms.size());
      if (conditions[c] == "white" && bit_rate >= kEveryRoomBitRate && good == static_cast<int>(rooms.size())) every_met = true;
      std::printf("rate %d %-8s %6.1f bit/s, %-9s: %2d of %zu room-ears >= %d/%d, frames %5.1f %%, wrong %d\n", rate,
                  RateLabel(*profile, rate).c_str(), bit_rate, conditions[c].c_str(), good, rooms.size(), bar, request.frames,
                  100.0 * right / std::max(1.0, static_cast<double>(rooms.size()) * request.frames), wrong);
    }
    const double times = audio / std::max(1e-9, cpu);
    speed_met = speed_met && times >= kRealTimes;
    std::printf("rate %d %-8s decodes at %.0fx real time on one core\n", rate, RateLabel(*profile, rate).c_str(), times);
    if (bit_rate >= kFastBitRate && all_conditions_three_quarters) fast_met = true;
  }
  std::printf("target: a rate of >= %.0f bit/s delivering in 3/4 of the room-ears under every condition: %s (fastest run: %.1f bit/s)\n",
              kFastBitRate, fast_met ? "yes" : "NO", fastest);
  std::printf("target: a rate of >= %.0f bit/s delivering in every room-ear under white noise: %s\n", kEveryRoomBitRate,
              every_met ? "yes" : "NO");
  std::printf("target: no wrong frame: %s\n", none_wrong ? "yes" : "NO");
  std::printf("target: every rate decodes at >= %.0fx real time: %s\n", kRealTimes, speed_met ? "yes" : "NO");
  return 0;
}

}  // namespace nava_modem::tools
