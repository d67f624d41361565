// ranging_bench: two-way acoustic ranging measured end to end on rendered scenes. For each
// scene, robots stand at random places of a shipped world with acoustics (a reverberation time
// and a background level drawn for the scene); each sends packets in turn; the scene renderer
// (scene_render.h) gives every robot's microphone what it hears, its own packets included, on a
// sound card of its own (a clock within +-100 ppm, an unknown playback latency); the real
// receiver of the profile decodes and times every recording; each robot's TwoWayRanger
// (ranging/two_way_ranger.h) takes the team's timings, as over ROS; each range is compared with
// the length of the shortest way round the walls.
//
//   ranging_bench [--worlds maps/office_team20_world.yaml,maps/campus_team60_world.yaml] [--teams 2,5,10,20]
//                 [--scenes 2] [--rounds 2] [--profile room] [--rate 48000] [--seed 1]
//                 [--plot ranging_error.png] [--threads 2]
//
// One line per scene, then over every scene:
//   ranging: line of sight median X cm, p90 Y cm; round corners median Z % of path; bearing+range
//   position median W cm at <= 5 m
// and the targets (line of sight up to 15 m: median <= 3 cm, p90 <= 10 cm; round corners: median
// within 3 % of the path; position median <= 10 cm). Round-corner pairs whose direct sound is
// within 20 dB of the reverberation are also reported apart. A position is the two-way range
// along the bearing a 10 cm square of four microphones gives on the teammate's packet rendered
// through the same link (RenderRoomArray, the real direction estimator). The PNG shows the
// error's median and 90th percentile against distance.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "acoustic_world.h"
#include "audio_propagation/acoustic_model.h"
#include "audio_propagation/scene_render.h"
#include "audio_propagation_args.h"
#include "nava_modem/array_decode.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/moved_rooms.h"
#include "nava_modem/room_array.h"
#include "ranging/two_way_ranger.h"
#include "tool_args/line_chart.h"
#include "tool_args/parallel_for.h"

namespace {

using namespace audio_propagation;

constexpr double kMaxLineOfSight = 15.0;  // m: the line-of-sight target's reach
constexpr double kTeamRadius = 12.0;      // m: robots are placed within this of the first
constexpr double kWallClearance = 0.4;    // m
constexpr double kPositionReach = 5.0;    // m: the position target's reach
constexpr double kSquareHalf = 0.05;      // m: the array, a 10 cm square as nava_bench --doa's
// Round a corner, the pairs whose direct sound is within this of the reverberation are also
// reported apart: below it the direct sound is found only where the noise is low enough.
constexpr double kClearDrrDb = -20.0;

struct Pair {
  std::size_t team = 0;  // robots in the scene
  double truth = 0.0;    // m, the shortest way
  int corners = 0;
  double drr_db = 0.0;  // the weaker direction's direct-to-reverberant ratio, as the model predicts it
  double error = 0.0;   // m, range - truth
  // m: the teammate's place from the range and the bearing a 4-microphone square gives, against
  // its true place (line of sight within kPositionReach only; NaN otherwise or without a bearing)
  double position_error = std::numeric_limits<double>::quiet_NaN();
};

struct SceneResult {
  std::string line;
  std::vector<Pair> pairs;
};

// A free place at least kWallClearance from any wall, within `radius` of `around` (any free
// place when radius is 0).
Eigen::Vector2d FreePlace(const grid::OccupancyMap& map, std::mt19937& rng, const Eigen::Vector2d& around, double radius) {
  std::uniform_real_distribution<double> ux(0.0, map.width_m()), uy(0.0, map.height_m()), u(-1.0, 1.0);
  for (int tries = 0; tries < 100000; ++tries) {
    Eigen::Vector2d p = radius > 0.0 ? Eigen::Vector2d(around + radius * Eigen::Vector2d(u(rng), u(rng)))
                                     : Eigen::Vector2d(map.origin().x + ux(rng), map.origin().y + uy(rng));
    bool clear = true;
    for (int k = 0; k < 8 && clear; ++k) {
      const double a = k * M_PI / 4.0;
      clear = map.IsFreeAt(p + kWallClearance * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    if (clear && map.IsFreeAt(p)) return p;
  }
  throw std::runtime_error("no free place found on the map");
}

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

// Where robot r puts teammate o (`offset`, its true place from r; r faces +x): o's packet as a
// 10 cm square of four microphones on r hears it in the scene's room (RenderRoomArray: the
// link's DRR and SNR as the model gives them), its bearing from the real direction estimator
// (DecodeArray), at the two-way range. NaN when no direction comes out.
double PositionError(const nava_modem::ModemProfile& profile, double rate, const PacketHearing& link,
                     const ScenePacket& packet, double rt60, const ranging::Range& range, const Eigen::Vector2d& offset,
                     std::uint32_t seed) {
  const std::vector<nava_modem::Microphone2D> mics = {
      {kSquareHalf, kSquareHalf}, {-kSquareHalf, kSquareHalf}, {-kSquareHalf, -kSquareHalf}, {kSquareHalf, -kSquareHalf}};
  std::vector<float> clean(static_cast<std::size_t>(0.2 * rate), 0.0f);
  const std::vector<float> burst = profile.ModulatePacket({packet.data.begin(), packet.data.end()});
  clean.insert(clean.end(), burst.begin(), burst.end());
  clean.resize(clean.size() + static_cast<std::size_t>(0.5 * rate), 0.0f);
  nava_modem::RoomOptions room;
  room.rt60 = rt60;
  room.drr_db = std::clamp(link.prediction.signal.drr_db, -40.0, 40.0);
  room.noise = nava_modem::RoomOptions::Noise::kPink;
  room.snr_db = std::min(60.0, link.prediction.snr_db);
  room.seed = seed + static_cast<std::uint32_t>(link.packet);
  nava_modem::ArraySource source;
  source.mics = mics;
  source.bearing = std::atan2(offset.y(), offset.x());
  source.distance = offset.norm();
  const auto channels = nava_modem::RenderRoomArray(clean, rate, room, source);
  const auto events = nava_modem::DecodeArray(profile, nava_modem::ReceiverOptions{}, channels, mics);
  for (const nava_modem::RxEvent& e : events) {
    if (e.kind != nava_modem::RxEvent::Kind::kPacket || !std::isfinite(e.direction)) continue;
    const Eigen::Vector2d estimate = range.range * Eigen::Vector2d(std::cos(e.direction), std::sin(e.direction));
    return (estimate - offset).norm();
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// The table and the measured rooms (when the table was measured over them) are loaded once for
// every scene.
SceneResult RunScene(const tools::RangingBenchArgs& args, const tools::AcousticWorld& world, const DecodeTable& table,
                     const std::shared_ptr<const nava_modem::MovedRooms>& measured_rooms, std::size_t team,
                     std::uint32_t seed) {
  std::mt19937 rng(seed);
  // The scene's room: one reverberation time everywhere, no noise sources, a background level
  // that leaves links from about 0 to 20 dB of SNR.
  world_sim::Acoustics acoustics = world.acoustics;
  const double rt60 = std::uniform_real_distribution<double>(0.3, 1.0)(rng);
  acoustics.room.rt60 = rt60;
  for (world_sim::AcousticRegion& r : acoustics.regions) r.room.rt60 = rt60;
  acoustics.noise_sources.clear();
  acoustics.ambient_db = std::uniform_real_distribution<double>(35.0, 50.0)(rng);
  acoustics.ambient_kind = world_sim::NoiseKind::kPink;

  const grid::OccupancyMap& map = world.loaded.map;
  Scene scene;
  scene.profile = args.profile;
  scene.own_packets = true;
  std::vector<Eigen::Vector2d> places;
  places.push_back(FreePlace(map, rng, {}, 0.0));
  while (places.size() < team) places.push_back(FreePlace(map, rng, places.front(), kTeamRadius));
  std::uniform_real_distribution<double> ppm(-100.0, 100.0), latency(0.0, 0.05);
  std::vector<std::string> names;
  for (std::size_t r = 0; r < team; ++r) {
    SceneRobot robot;
    robot.name = world.robots[r];
    robot.keyframes.push_back({0.0, places[r].x(), places[r].y(), 0.0});
    scene.robots.push_back(robot);
    scene.sound_cards[robot.name] = SceneSoundCard{ppm(rng) * 1e-6, latency(rng)};
    names.push_back(robot.name);
  }
  // Each robot in turn, one packet at a time: a slot holds the packet, the longest travel and
  // the latencies.
  nava_modem::ModemOptions modem;
  modem.sample_rate = args.rate;
  const auto profile = nava_modem::MakeProfile(args.profile, modem);
  const double airtime = static_cast<double>(profile->ModulatePacket({1, 2, 3, 4}).size()) / args.rate;
  const double slot = airtime + 0.25;
  double t = 0.3;
  for (int round = 0; round < args.rounds; ++round) {
    for (std::size_t r = 0; r < team; ++r, t += slot) {
      ScenePacket p;
      p.time = t;
      p.sender = names[r];
      const std::size_t id = scene.packets.size();
      p.data = {static_cast<std::uint8_t>(id & 0xFF), static_cast<std::uint8_t>(id >> 8), 0x5A,
                static_cast<std::uint8_t>(r)};
      scene.packets.push_back(p);
    }
  }
  scene.duration = t + 0.5;

  const AcousticModel model(*world.propagation, acoustics, table, world.robots);
  SceneRenderOptions options;
  options.sample_rate = args.rate;
  options.seed = seed;
  options.measured_rooms = measured_rooms;
  const SceneRenderer renderer(model, world.robots, world.resting, options);
  const SceneRendering rendering = renderer.Render(scene);

  // Every listener's recording decoded and timed by the real receiver, as its link would.
  std::vector<std::vector<nava_modem::RxEvent>> heard(team);
  multirobot_audio::tools::ParallelFor(team, args.threads, [&](std::size_t l) {
    const std::vector<float> mix = rendering.listeners[l].Mix();
    const auto receiver = profile->MakeReceiver(nava_modem::ReceiverOptions{});
    receiver->Process(mix.data(), mix.size(), heard[l]);
    receiver->Flush(heard[l]);
  });
  std::vector<ranging::Timing> timings;
  std::size_t decoded = 0, timed = 0;
  for (std::size_t l = 0; l < team; ++l) {
    for (const nava_modem::RxEvent& e : heard[l]) {
      if (e.kind != nava_modem::RxEvent::Kind::kPacket || e.data.size() != 4) continue;
      const std::size_t id = e.data[0] | (static_cast<std::size_t>(e.data[1]) << 8);
      if (id >= scene.packets.size() || e.data[3] >= team) continue;
      ++decoded;
      if (!std::isfinite(e.arrival)) continue;
      ++timed;
      ranging::Timing timing;
      timing.sender = names[e.data[3]];
      timing.listener = names[l];
      timing.data = e.data;
      timing.arrival = e.arrival;
      timing.rate_error = timing.sender == timing.listener ? 0.0 : e.rate_error;
      timing.stamp = scene.packets[id].time;
      timings.push_back(timing);
    }
  }
  // In the order they happened (each listener's in the order of its clock).
  std::stable_sort(timings.begin(), timings.end(),
                   [](const ranging::Timing& a, const ranging::Timing& b) { return a.stamp < b.stamp; });
  ranging::RangerOptions ranger;
  ranger.speed_of_sound = world.propagation->options().speed_of_sound;
  ranger.pair_window = 2.0 * slot * static_cast<double>(team) + 1.0;
  // Each robot hears itself from self_distance away: what a robot calibrates ~ranging_offset for.
  ranger.offset = scene.self_distance;
  SceneResult result;
  std::size_t ranged = 0, wanted = 0;
  for (std::size_t r = 0; r < team; ++r) {
    ranging::TwoWayRanger robot(names[r], names, ranger);
    for (const ranging::Timing& timing : timings) robot.Add(timing);
    for (std::size_t o = 0; o < team; ++o) {
      if (o == r) continue;
      const SoundPath path = world.propagation->Path(places[r], places[o]);
      if (!path.reachable) continue;
      ++wanted;
      const auto range = robot.RangeTo(names[o], scene.duration);
      if (!range) continue;
      ++ranged;
      double drr = std::numeric_limits<double>::infinity();
      for (const PacketHearing& h : rendering.hearings) {
        const std::string& from = scene.packets[h.packet].sender;
        if (h.reachable && ((from == names[r] && h.listener == names[o]) || (from == names[o] && h.listener == names[r]))) {
          drr = std::min(drr, h.prediction.signal.drr_db);
        }
      }
      Pair pair{team, path.length, path.bends, drr, range->range - path.length};
      if (path.bends == 0 && path.length <= kPositionReach) {
        const PacketHearing* link = nullptr;
        for (const PacketHearing& h : rendering.hearings) {
          if (h.reachable && scene.packets[h.packet].sender == names[o] && h.listener == names[r]) link = &h;
        }
        if (link) pair.position_error = PositionError(*profile, args.rate, *link, scene.packets[link->packet], rt60, *range,
                                                      places[o] - places[r], seed);
      }
      result.pairs.push_back(pair);
    }
  }
  std::vector<double> errors;
  for (const Pair& p : result.pairs) errors.push_back(std::abs(p.error) * 100.0);
  char line[256];
  std::snprintf(line, sizeof line,
                "%-28s %2zu robots, rt60 %.2f s, ambient %.0f dB: %zu packets decoded, %zu timed; %zu of %zu pairs "
                "ranged, |error| median %.1f cm, worst %.1f cm",
                world.file.substr(world.file.find_last_of('/') + 1).c_str(), team, rt60, acoustics.ambient_db, decoded,
                timed, ranged, wanted, Quantile(errors, 0.5), Quantile(errors, 1.0));
  result.line = line;
  return result;
}

void Plot(const std::string& path, const std::vector<Pair>& pairs) {
  multirobot_audio::tools::LineChart chart;
  chart.title = "two-way ranging on rendered scenes: |range - shortest path| by distance";
  chart.x_label = "shortest path, m";
  chart.y_label = "|error|, cm (at most 100 drawn)";
  double top = 10.0;
  for (const bool los : {true, false}) {
    multirobot_audio::tools::LineSeries median, p90;
    median.label = std::string(los ? "line of sight" : "round corners") + ", median";
    p90.label = std::string(los ? "line of sight" : "round corners") + ", 90th percentile";
    median.colour = p90.colour = los ? 0 : 1;
    p90.style = multirobot_audio::tools::LineSeries::Style::kDashed;
    for (double from = 0.0; from < 25.0; from += 2.5) {
      std::vector<double> bin;
      for (const Pair& p : pairs) {
        if ((p.corners == 0) == los && p.truth >= from && p.truth < from + 2.5) bin.push_back(std::abs(p.error) * 100.0);
      }
      if (bin.empty()) continue;
      median.x.push_back(from + 1.25);
      median.y.push_back(Quantile(bin, 0.5));
      p90.x = median.x;
      p90.y.push_back(Quantile(bin, 0.9));
      top = std::max(top, p90.y.back());
    }
    chart.series.push_back(median);
    chart.series.push_back(p90);
  }
  chart.y_max = std::min(100.0, 1.1 * top);
  multirobot_audio::tools::WriteLineChart(path, chart);
}

int Run(const tools::RangingBenchArgs& args) {
  std::vector<tools::AcousticWorld> worlds;
  for (const std::string& file : args.worlds) worlds.push_back(tools::LoadAcousticWorld("ranging_bench", file, ""));
  std::printf("ranging_bench: %s packets at %.0f Hz, %d rounds, %d scenes per world and team size\n",
              nava_modem::ProfileName(args.profile), args.rate, args.rounds, args.scenes);
  const DecodeTable table = tools::LoadTable("ranging_bench", args.profile, "");
  const std::shared_ptr<const nava_modem::MovedRooms> measured_rooms =
      tools::MeasuredRoomsFor(table, args.rir_dir, args.rate, args.usage);
  std::vector<Pair> pairs;
  std::uint32_t seed = args.seed;
  for (const tools::AcousticWorld& world : worlds) {
    for (const int team : args.teams) {
      if (static_cast<std::size_t>(team) > world.robots.size()) {
        std::printf("%s has %zu robots: no team of %d\n", world.file.c_str(), world.robots.size(), team);
        continue;
      }
      for (int s = 0; s < args.scenes; ++s) {
        const SceneResult r = RunScene(args, world, table, measured_rooms, static_cast<std::size_t>(team), seed++);
        std::printf("%s\n", r.line.c_str());
        std::fflush(stdout);
        pairs.insert(pairs.end(), r.pairs.begin(), r.pairs.end());
      }
    }
  }
  std::vector<double> los, corners, clear_corners, positions;
  std::size_t position_tries = 0;
  for (const Pair& p : pairs) {
    if (p.corners == 0 && p.truth <= kMaxLineOfSight) los.push_back(std::abs(p.error) * 100.0);
    if (p.corners > 0) corners.push_back(std::abs(p.error) / p.truth * 100.0);
    if (p.corners > 0 && p.drr_db >= kClearDrrDb) clear_corners.push_back(std::abs(p.error) / p.truth * 100.0);
    if (p.corners == 0 && p.truth <= kPositionReach) {
      ++position_tries;
      if (std::isfinite(p.position_error)) positions.push_back(p.position_error * 100.0);
    }
  }
  const double los_median = Quantile(los, 0.5), los_p90 = Quantile(los, 0.9), corner_median = Quantile(corners, 0.5);
  std::printf("pairs ranged: %zu in line of sight up to %.0f m, %zu round corners (%zu of them with DRR >= %.0f dB)\n",
              los.size(), kMaxLineOfSight, corners.size(), clear_corners.size(), kClearDrrDb);
  std::printf("round corners with DRR >= %.0f dB: median %.1f %% of path, p90 %.1f %%\n", kClearDrrDb,
              Quantile(clear_corners, 0.5), Quantile(clear_corners, 0.9));
  const double position_median = Quantile(positions, 0.5);
  std::printf("positions from range and bearing: %zu of %zu line-of-sight pairs within %.0f m gave a bearing, p90 %.1f cm\n",
              positions.size(), position_tries, kPositionReach, Quantile(positions, 0.9));
  std::printf("ranging: line of sight median %.1f cm, p90 %.1f cm; round corners median %.1f %% of path; bearing+range "
              "position median %.1f cm at <= %.0f m\n",
              los_median, los_p90, corner_median, position_median, kPositionReach);
  std::printf("target: line of sight median <= 3 cm and p90 <= 10 cm: %s; round corners median <= 3 %%: %s; position "
              "median <= 10 cm: %s\n",
              los_median <= 3.0 && los_p90 <= 10.0 ? "yes" : "NO", corner_median <= 3.0 ? "yes" : "NO",
              position_median <= 10.0 ? "yes" : "NO");
  if (!args.plot.empty()) {
    Plot(args.plot, pairs);
    std::printf("wrote %s\n", args.plot.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool(
      [&] { return Run(audio_propagation::tools::ParseRangingBenchArgs(multirobot_audio::tools::Words(argc, argv))); });
}
