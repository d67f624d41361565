// audio_channel_validate: how well the `acoustic` channel model predicts the real receiver
// (channel_validation.h). Random links between free points at least 0.3 m from walls (in the free
// space the world's robots stand in), each at a random moment of the noise sources' duty cycles:
// the model's decode probability (Predict with the noise of that moment) against the real
// receiver's decode of K packets rendered at the listener by the scene renderer.
//
//   audio_channel_validate --world W [--map M] [--profile nava|room] [--links 300] [--packets 4]
//                          [--table FILE] [--seed 1] [--out DIR] [--threads 2]
//   audio_channel_validate --world W [--map M] [--profile P] [--table FILE] [--time 0]
//                          --predict X1,Y1 X2,Y2
//   audio_channel_validate --world W [--map M] [--profile P] [--table FILE] [--seed 1]
//                          --static-pairs N [--pair-packets 30] [--fate-distance 0.075]
//
// Prints a table per path-length bin (0-3, 3-6, 6-10, 10-15, 15-20, 20-30, 30+ m; a bin of fewer
// than 15 links merged into its neighbour): links, the model's and the rendered delivery and the
// noise gap (the rendered noise during the packets against the model's), then the packets by the
// model's SNR, by its loudest disturbance and by the noise gap, and
//   agreement: max |model - rendered| = X points over K distance bins
// and writes DIR/validate_<profile>.png (delivery against path length, both). Links run on
// --threads threads; the same seed gives the same output. The table defaults to the profile's
// shipped one.
// With --static-pairs: N static and N moving pairs of places whose model probability is 20-80 %,
// each sending --pair-packets packets through the simulated acoustic channel (fate_check.h), with
// the links' fate held and, for comparison, drawn anew for every packet:
//   static: K of N pairs deliver under 10 % or over 90 % of their packets in steady noise
//   static, the sources on their duty cycles: K of N pairs deliver under 10 % or over 90 %
//   moving: N pairs, mean delivery X % against the model's Y %
// With --rooms: the rooms the world's acoustics.rooms cuts its map into (floor area, centre,
// volume, RT60, critical distance, absorption, the region naming it) and the openings between them (width, centre); with
// --from X,Y also each room's reverberant field from a source there, in dB against the field the
// source would make in its own room shut in (coupled_rooms.h); with --plot FILE.png also the level
// a microphone hears from that source across the map (direct and reverberant, 0.25 m squares),
// with one reverberant field and with the rooms, side by side.
// With --predict: one JSON line for a packet from (X1, Y1) to (X2, Y2) at time --time (the world's
// robots where the world puts them), no rendering: path_length, corners, direct_db,
// reverberant_db, noise_db, drr_db, snr_db, rt60, kind, probability (null figures without a path).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <sstream>

#include "acoustic_world.h"
#include "bench_support/child_process.h"
#include "audio_propagation_args.h"
#include "audio_propagation/room_coupling.h"
#include "tool_args/heat_map.h"
#include "tool_args/line_chart.h"

namespace {

using namespace audio_propagation;

constexpr int kMinBinLinks = 15;

std::string Json(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", v);
  return text;
}

int Predict(const tools::ValidateArgs& args, const tools::AcousticWorld& world, const DecodeTable& table) {
  const Eigen::Vector2d& from = args.from;
  const Eigen::Vector2d& to = args.to;
  const double time = args.time;
  for (const Eigen::Vector2d& p : {from, to}) {
    if (!world.loaded.map.IsFreeAt(p)) {
      std::ostringstream s;
      s << "--predict: (" << p.x() << ", " << p.y() << ") is not in the map's free space";
      args.usage.Fail(s.str());
    }
  }
  const AcousticModel model(*world.propagation, world.acoustics, table, world.robots);
  const SoundPath path = world.propagation->Path(from, to);
  if (!path.reachable) {
    std::printf("{\"path_length\": null, \"corners\": null, \"direct_db\": null, \"reverberant_db\": null, "
                "\"noise_db\": null, \"drr_db\": null, \"snr_db\": null, \"rt60\": null, \"kind\": null, "
                "\"probability\": 0}\n");
    return 0;
  }
  const LinkPrediction p = model.Predict(path, to, model.NoiseAt(to, time, world.resting));
  std::printf("{\"path_length\": %s, \"corners\": %d, \"direct_db\": %s, \"reverberant_db\": %s, \"noise_db\": %s, "
              "\"drr_db\": %s, \"snr_db\": %s, \"rt60\": %s, \"kind\": \"%s\", \"probability\": %s}\n",
              Json(p.path_length).c_str(), p.corners, Json(p.signal.direct_db).c_str(),
              Json(p.signal.reverberant_db).c_str(), Json(p.noise_db).c_str(), Json(p.signal.drr_db).c_str(),
              Json(p.snr_db).c_str(), Json(p.signal.rt60).c_str(), InterferenceName(p.kind),
              Json(p.probability).c_str());
  return 0;
}

// The level a microphone hears across the map from a source at `from` (AcousticModel::Levels,
// total), on squares of at least 0.25 m; NaN off the free space or where no path reaches.
multirobot_audio::tools::HeatPanel LevelPanel(const tools::AcousticWorld& world, const world_sim::Acoustics& acoustics,
                                              const DecodeTable& table, const Eigen::Vector2d& from,
                                              const std::string& title) {
  const AcousticModel model(*world.propagation, acoustics, table, world.robots);
  const grid::OccupancyMap& map = world.loaded.map;
  const int stride = grid::CellsAcross(map, 0.25);
  multirobot_audio::tools::HeatPanel panel;
  panel.title = title;
  panel.width = map.width() / stride;
  panel.height = map.height() / stride;
  panel.values.assign(static_cast<std::size_t>(panel.width) * panel.height, std::nan(""));
  std::vector<Eigen::Vector2d> listeners;
  std::vector<std::size_t> index;
  for (int j = 0; j < panel.height; ++j) {
    for (int i = 0; i < panel.width; ++i) {
      const Eigen::Vector2d centre = map.CellCoordsToWorld(Eigen::Vector2d((i + 0.5) * stride, (j + 0.5) * stride));
      if (!map.IsFreeAt(centre)) continue;
      listeners.push_back(centre);
      index.push_back(static_cast<std::size_t>(j) * panel.width + i);
    }
  }
  const std::vector<SoundPath> paths = world.propagation->From(from, listeners);
  for (std::size_t k = 0; k < paths.size(); ++k) {
    if (paths[k].reachable) panel.values[index[k]] = model.Levels(paths[k], listeners[k]).total_db;
  }
  return panel;
}

int Rooms(const tools::ValidateArgs& args, const tools::AcousticWorld& world) {
  if (!world.acoustics.rooms) {
    args.usage.Fail("--rooms: " + args.world_file + " has no acoustics.rooms section (one reverberant field fills it)");
  }
  const RoomCoupling rooms(world.loaded.map, world.acoustics);
  const grid::RoomSegmentation& cut = rooms.segmentation();
  int source = -1;  // the source's zone
  if (args.rooms_from) {
    source = rooms.ZoneAt(*args.rooms_from);
    if (source < 0) {
      std::ostringstream s;
      s << "--from: (" << args.rooms_from->x() << ", " << args.rooms_from->y() << ") is not in the map's free space";
      args.usage.Fail(s.str());
    }
    std::printf("a source at (%.2f, %.2f), in room %d\n", args.rooms_from->x(), args.rooms_from->y(),
                rooms.RoomAt(*args.rooms_from));
  }
  const std::vector<RoomZones::Zone>& zones = rooms.zones().zones();
  const CoupledRooms& field = rooms.field();
  auto field_db = [&](std::size_t zone) { return field.RelativeLevelDb(static_cast<std::size_t>(source), zone); };
  std::printf("%zu rooms, %zu openings, %zu zones\n", cut.rooms().size(), cut.openings().size(), zones.size());
  std::printf("room   centre (m)        area m^2  volume m^3  rt60 s  r_c m  absorption m^2  region  zones%s\n",
              source >= 0 ? "  field dB" : "");
  for (std::size_t k = 0; k < cut.rooms().size(); ++k) {
    const grid::SegmentedRoom& r = cut.rooms()[k];
    const world_sim::RoomAcoustics& a = rooms.Acoustics(k);
    // A room cut into zones is their sum; its field, the loudest of them.
    double volume = 0.0, absorption = 0.0, loudest = -1e300;
    for (std::size_t z = 0; z < zones.size(); ++z) {
      if (zones[z].room != static_cast<int>(k)) continue;
      volume += field.rooms()[z].volume;
      absorption += field.Absorption(z);
      if (source >= 0) loudest = std::max(loudest, field_db(z));
    }
    const int region = rooms.Region(k);
    std::printf("%4zu  (%6.2f, %6.2f)  %9.1f  %10.1f  %6.2f  %5.2f  %14.1f  %-6s  %5d", k, r.centroid.x(), r.centroid.y(),
                r.area, volume, a.rt60, world_sim::CriticalDistance(a), absorption,
                region < 0 ? "-" : world.acoustics.regions[static_cast<std::size_t>(region)].name.c_str(),
                rooms.zones().ZonesOf(k));
    if (source >= 0) std::printf("  %+8.1f", loudest);
    std::printf("\n");
  }
  if (zones.size() > cut.rooms().size()) {
    std::printf("zone  room  area m^2  absorption m^2%s   (long rooms cut along their length)\n",
                source >= 0 ? "  field dB" : "");
    for (std::size_t z = 0; z < zones.size(); ++z) {
      if (rooms.zones().ZonesOf(static_cast<std::size_t>(zones[z].room)) < 2) continue;
      std::printf("%4zu  %4d  %8.1f  %14.1f", z, zones[z].room, zones[z].area, field.Absorption(z));
      if (source >= 0) std::printf("  %+8.1f", field_db(z));
      std::printf("\n");
    }
  }
  std::printf("opening  rooms     width m  centre (m)\n");
  for (std::size_t k = 0; k < cut.openings().size(); ++k) {
    const grid::SegmentedOpening& o = cut.openings()[k];
    std::printf("%7zu  %3d-%-3d  %8.2f  (%6.2f, %6.2f)\n", k, o.a, o.b, o.width, o.center.x(), o.center.y());
  }
  if (!args.rooms_plot.empty()) {
    // The model needs a table to be built; the levels do not depend on it.
    const DecodeTable table = tools::LoadTable("audio_channel_validate", args.validation.profile, args.table_file);
    world_sim::Acoustics single = world.acoustics;
    single.rooms.reset();
    multirobot_audio::tools::HeatMaps maps;
    maps.unit = "dB";
    maps.low = 20.0;
    maps.high = 75.0;
    maps.pixels_per_cell = 6;
    maps.panels = {LevelPanel(world, single, table, *args.rooms_from, "one reverberant field"),
                   LevelPanel(world, world.acoustics, table, *args.rooms_from, "coupled rooms")};
    multirobot_audio::tools::WriteHeatMaps(args.rooms_plot, maps);
    std::printf("plot: %s (the level heard from (%.2f, %.2f), dB)\n", args.rooms_plot.c_str(), args.rooms_from->x(),
                args.rooms_from->y());
  }
  return 0;
}

// Delivery of a group of packets, in %.
struct Group {
  int links = 0, packets = 0, decoded = 0, gaps = 0;
  double model = 0.0, noise_gap = 0.0;
  void Add(const JudgedPacket& p) {
    ++packets;
    model += p.probability;
    decoded += p.decoded;
    if (std::isfinite(p.noise_gap_db)) {
      noise_gap += p.noise_gap_db;
      ++gaps;
    }
  }
  void Add(const ValidationLink& l) {
    ++links;
    for (const JudgedPacket& p : l.judged) Add(p);
    packets += l.packets - static_cast<int>(l.judged.size());  // no path: neither decodes
  }
  // The first column counts links, or packets where the group was filled packet by packet.
  void Print(const std::string& label) const {
    if (packets == 0) return;
    std::printf("  %-16s %7d %9.1f %11.1f %+7.1f %+10.1f\n", label.c_str(), links ? links : packets,
                100.0 * model / packets, 100.0 * decoded / packets, 100.0 * (model - decoded) / packets,
                gaps ? noise_gap / gaps : 0.0);
  }
};

std::string Range(double low, double high) {
  char text[32];
  if (std::isinf(high)) {
    std::snprintf(text, sizeof text, "%g+", low);
  } else {
    std::snprintf(text, sizeof text, "%g-%g", low, high);
  }
  return text;
}

int StaticPairs(const tools::ValidateArgs& args, const tools::AcousticWorld& world, const DecodeTable& table) {
  std::printf("audio_channel_validate: %s, profile %s, %d static and %d moving pairs of places at model probability "
              "20-80 %%, %d packets each, fate distance %g m, seed %u\n",
              args.world_file.c_str(), args.profile_name.c_str(), args.fate.pairs, args.fate.pairs, args.fate.packets,
              args.fate.fate_distance, args.fate.seed);
  for (const bool fate : {true, false}) {
    FateCheckOptions o = args.fate;
    o.link_fate = fate;
    const FateCheckResult r = CheckLinkFate(*world.propagation, world.acoustics, table, world.robots, world.resting, o);
    const char* how = fate ? "" : " (every packet drawn anew)";
    std::printf("static: %d of %d pairs deliver under 10 %% or over 90 %% of their packets in steady noise%s\n",
                r.static_decided, r.static_pairs, how);
    std::printf("static, the sources on their duty cycles: %d of %d pairs deliver under 10 %% or over 90 %%%s\n",
                r.cycling_decided, r.cycling_pairs, how);
    std::printf("moving: %d pairs, mean delivery %.1f %% against the model's %.1f %%%s\n", r.moving_pairs,
                100.0 * r.moving_delivered, 100.0 * r.moving_probability, how);
    if (r.static_pairs < o.pairs || r.cycling_pairs < o.pairs || r.moving_pairs < o.pairs) {
      std::printf("  (only these pairs found at 20-80 %% in %d draws of places)\n", r.draws);
    }
    std::fflush(stdout);
  }
  return 0;
}

int Run(const tools::ValidateArgs& args) {
  const std::string program = "audio_channel_validate";
  const std::string& world_file = args.world_file;
  const std::string& profile_name = args.profile_name;
  const std::string& table_file = args.table_file;
  const std::string& out = args.out;
  ValidationOptions options = args.validation;

  const double cpu_start = bench_support::CpuNow();
  const auto wall_start = std::chrono::steady_clock::now();
  const tools::AcousticWorld world = tools::LoadAcousticWorld(program, world_file, args.map_file);
  if (args.rooms) {
    try {
      return Rooms(args, world);
    } catch (const std::exception& e) {
      tools::Fail(program, world_file + ": " + e.what());
    }
  }
  const DecodeTable table = tools::LoadTable(program, options.profile, table_file);
  if (args.predict) {
    try {
      return Predict(args, world, table);
    } catch (const std::exception& e) {
      tools::Fail(program, e.what());
    }
  }
  if (args.static_pairs > 0) {
    try {
      return StaticPairs(args, world, table);
    } catch (const std::exception& e) {
      tools::Fail(program, world_file + ": " + e.what());
    }
  }
  options.speech = tools::SpeechFor(program, world.acoustics, options.sample_rate, options.seed);
  options.measured_rooms = tools::MeasuredRoomsFor(table, args.rir_dir, options.sample_rate, args.usage);
  // The acoustic channel's propagation model (threshold 30 dB under the ambient noise, as the
  // node sets it) computes no path longer than this.
  PropagationOptions channel_paths;
  channel_paths.threshold_db = std::min(channel_paths.source_level_db, AcousticThresholdDb(world.acoustics));
  const double channel_hearing = PropagationModel(grid::OccupancyMap(1, 1, 1.0), channel_paths).HearingDistance();
  options.channel_hearing_distance = channel_hearing;

  std::printf("%s: %s, profile %s, table %s (%s), %d links of %d packets, seed %u\n", program.c_str(),
              world_file.c_str(), profile_name.c_str(), table_file.empty() ? "shipped" : table_file.c_str(),
              table.command.c_str(), options.links, options.packets, options.seed);
  std::fflush(stdout);
  std::vector<ValidationLink> links;
  try {
    links = ValidateLinks(*world.propagation, world.acoustics, table, world.robots, world.resting, options, [&](int done) {
      if (done % std::max(1, options.links / 10) == 0) std::fprintf(stderr, "  %d/%d links\n", done, options.links);
    });
  } catch (const std::exception& e) {
    tools::Fail(program, world_file + ": " + e.what());
  }

  const std::vector<double> edges(std::begin(kDefaultEdges), std::end(kDefaultEdges));
  const std::vector<DistanceBin> bins = BinByLength(links, edges, kMinBinLinks);
  std::printf("  %-16s %7s %9s %11s %7s %10s\n", "path (m)", "links", "model %", "rendered %", "diff", "noise gap");
  for (const DistanceBin& b : bins) {
    Group g;
    for (const ValidationLink& l : links) {
      if (l.path_length >= b.low && (l.path_length < b.high || std::isinf(b.high))) g.Add(l);
    }
    g.Print(Range(b.low, b.high));
  }
  // The same packets grouped by what the model saw (the count is of packets).
  std::vector<JudgedPacket> packets;
  for (const ValidationLink& l : links) packets.insert(packets.end(), l.judged.begin(), l.judged.end());
  auto print_by = [&](const char* title, const std::vector<std::pair<std::string, std::function<bool(const JudgedPacket&)>>>& rows) {
    std::printf("%s\n", title);
    for (const auto& [label, holds] : rows) {
      Group g;
      for (const JudgedPacket& p : packets) {
        if (holds(p)) g.Add(p);
      }
      g.Print(label);
    }
  };
  std::vector<std::pair<std::string, std::function<bool(const JudgedPacket&)>>> by_snr, by_kind, by_gap;
  const double snr_edges[] = {-1e9, -5.0, 0.0, 5.0, 10.0, 15.0, 20.0, 1e9};
  for (std::size_t k = 0; k + 1 < std::size(snr_edges); ++k) {
    const double lo = snr_edges[k], hi = snr_edges[k + 1];
    by_snr.push_back({k == 0 ? "< -5" : k + 2 == std::size(snr_edges) ? ">= 20" : Range(lo, hi),
                      [lo, hi](const JudgedPacket& p) { return p.snr_db >= lo && p.snr_db < hi; }});
  }
  for (std::size_t k = 0; k < kInterferenceCount; ++k) {
    const Interference kind = static_cast<Interference>(k);
    by_kind.push_back({InterferenceName(kind), [kind](const JudgedPacket& p) { return p.kind == kind; }});
  }
  by_gap.push_back({"within 3 dB", [](const JudgedPacket& p) { return std::fabs(p.noise_gap_db) <= 3.0; }});
  by_gap.push_back({"louder by > 3", [](const JudgedPacket& p) { return p.noise_gap_db > 3.0; }});
  by_gap.push_back({"quieter by > 3", [](const JudgedPacket& p) { return p.noise_gap_db < -3.0; }});
  print_by("packets by the model's SNR (dB):", by_snr);
  print_by("packets by the model's loudest disturbance:", by_kind);
  print_by("packets by the rendered noise during them against the model's noise:", by_gap);
  int unreachable = 0;
  Group beyond;
  for (const ValidationLink& l : links) {
    if (l.beyond_hearing && l.reachable) beyond.Add(l);
    unreachable += !l.reachable;
  }
  std::printf("(noise gap: the rendered noise's level during a packet minus the model's unweighted sum of the "
              "disturbances, dB, mean; links without a path: %d)\n",
              unreachable);
  std::printf("links beyond the acoustic channel's reach (%.1f m, ~threshold_db), which the channel "
              "drops (0 %%) and the model above judges: %d",
              channel_hearing, beyond.links);
  if (beyond.packets > 0) {
    std::printf(", model %.1f %%, rendered %.1f %%", 100.0 * beyond.model / beyond.packets,
                100.0 * beyond.decoded / beyond.packets);
  }
  std::printf("\n");
  std::printf("agreement: max |model - rendered| = %.1f points over %zu distance bins\n", Agreement(bins), bins.size());

  multirobot_audio::tools::LineChart chart;
  chart.title = std::filesystem::path(world_file).filename().string() + ", " + profile_name +
                ": model and rendered delivery";
  chart.x_label = "path length (m), mean of each bin";
  chart.y_label = "packets decoded (%)";
  multirobot_audio::tools::LineSeries model_series, rendered_series;
  model_series.label = "model (table)";
  rendered_series.label = "rendered + decoded";
  rendered_series.colour = 1;
  rendered_series.style = multirobot_audio::tools::LineSeries::Style::kDashed;
  for (const DistanceBin& b : bins) {
    model_series.x.push_back(b.mean_length);
    model_series.y.push_back(b.model);
    rendered_series.x.push_back(b.mean_length);
    rendered_series.y.push_back(b.rendered);
  }
  chart.series = {model_series, rendered_series};
  const std::string plot = out + "/validate_" + profile_name + ".png";
  try {
    std::filesystem::create_directories(out);
    multirobot_audio::tools::WriteLineChart(plot, chart);
  } catch (const std::exception& e) {
    tools::Fail(program, e.what());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::printf("plot: %s\ncpu: %.1f s (wall %.1f s) on %d threads\n", plot.c_str(), bench_support::CpuNow() - cpu_start,
              wall, options.threads);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return multirobot_audio::tools::RunTool(
      [&] { return Run(audio_propagation::tools::ParseValidateArgs(multirobot_audio::tools::Words(argc, argv))); });
}
