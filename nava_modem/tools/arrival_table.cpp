#include "arrival_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "measured_rooms.h"
#include "nava_bench_support.h"
#include "nava_modem/first_arrival.h"
#include "nava_modem/modem_profile.h"
#include "nava_modem/room_channel.h"

namespace nava_modem::tools {
namespace {

constexpr double kTargetMedianS = 0.0001, kTargetP90S = 0.0003;
// Packet to packet, every room: the 90th percentile of how far its packets lie from the room's
// own median (precision, which ranging differences need, apart from the accuracy above).
constexpr double kTargetJitterP90S = 0.0001;

// The q-quantile of |errors| (nearest rank); NaN for none.
double AbsQuantile(std::vector<double> errors, double q) {
  if (errors.empty()) return std::nan("");
  for (double& e : errors) e = std::abs(e);
  std::sort(errors.begin(), errors.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(errors.size())));
  return errors[std::min(errors.size() - 1, rank == 0 ? 0 : rank - 1)];
}

// The signed errors less their median: how far each packet lies from the room's own typical
// arrival. Empty for none.
std::vector<double> AgainstMedian(std::vector<double> errors) {
  if (errors.empty()) return errors;
  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  for (double& e : errors) e -= median;
  return errors;
}

// The table the simulation's ranging draws timing errors from: the signed errors at 101 evenly
// spaced probabilities (linear between order statistics), with how they were measured. A
// hundred steps keep a rare outlier rare: the ranging draws linearly between neighbouring
// quantiles, and with 21 the one packet in ninety that a clap's reflection timed 8.5 ms late
// spread over the last twentieth of the draws.
void WriteErrors(const ArrivalRequest& r, std::vector<double> errors, int rooms, int sent) {
  std::sort(errors.begin(), errors.end());
  FILE* f = std::fopen(r.errors_out.c_str(), "w");
  if (!f) throw std::runtime_error("--errors-out " + r.errors_out + ": cannot write it");
  std::fprintf(f, "# First-arrival timing errors (arrival - (sent + the response's leading edge)) of the %s receiver\n"
                  "# through measured rooms: what the simulated team's ranging draws each timing's error from.\n",
               ProfileName(r.profile));
  std::fprintf(f, "profile: %s\n", ProfileName(r.profile));
  std::fprintf(f, "command: \"nava_bench --arrival --rir-dir %s --profile %s --packets %d --snr %g --min-drr %g --seed %u "
                  "--errors-out %s\"\n",
               r.rir_dir.c_str(), ProfileName(r.profile), r.packets, r.snr_db, r.min_drr_db, r.seed, r.errors_out.c_str());
  std::fprintf(f, "rooms: %d\npackets_sent: %d\npackets_timed: %zu\nsnr_db: %g\nmin_drr_db: %g\nquantiles_s: [", rooms, sent,
               errors.size(), r.snr_db, r.min_drr_db);
  constexpr int kQuantiles = 101;
  for (int k = 0; k < kQuantiles; ++k) {
    const double at = static_cast<double>(k) / (kQuantiles - 1) * static_cast<double>(errors.size() - 1);
    const std::size_t i = std::min(errors.size() - 2, static_cast<std::size_t>(at));
    const double q = errors[i] + (at - static_cast<double>(i)) * (errors[i + 1] - errors[i]);
    std::fprintf(f, "%s%.3e", k ? ", " : "", q);
  }
  std::fprintf(f, "]\n");
  if (std::fclose(f) != 0) throw std::runtime_error("--errors-out " + r.errors_out + ": writing it failed");
}

}  // namespace

int ArrivalTable(const ArrivalRequest& request, const multirobot_audio::tools::ToolUsage& usage) {
  const ModemOptions& options = request.options;
  const double fs = options.sample_rate;
  const std::vector<MeasuredRoom> rooms = MeasuredRooms(request.rir_dir, usage);
  const std::unique_ptr<ModemProfile> profile = MakeProfile(request.profile, options);
  std::mt19937 rng(request.seed);
  const CleanSignal clean = RandomPackets(*profile, request.packets, 0.6, 0.4, rng);
  std::vector<double> starts;  // where each packet begins in the clean signal, s
  for (int p = 0; p < request.packets; ++p) {
    starts.push_back(p == 0 ? std::floor(0.6 * fs) / fs : static_cast<double>(clean.ends[static_cast<std::size_t>(p) - 1]) / fs);
  }
  std::printf("first arrivals (%s): %d %s packets per room at %.0f Hz, white noise at SNR %.0f dB; "
              "error = arrival - (sent + the response's leading edge)\n",
              request.rir_dir.c_str(), request.packets, ProfileName(request.profile), fs, request.snr_db);
  std::printf("%-44s %7s %6s %7s %10s %10s %10s %10s\n", "room", "drr_dB", "rt60_s", "timed", "median_us", "p90_us",
              "worst_us", "jitter_us");
  std::vector<double> counted;
  // Each room's jitter p90 (every room, whatever its DRR), and the worst room's.
  std::vector<double> jitters;
  std::string worst_jitter_room;
  double worst_jitter = -1.0;
  int counted_rooms = 0, counted_sent = 0;
  for (const MeasuredRoom& room : rooms) {
    const std::vector<float> response = LoadImpulseResponse(room.path, room.channel, fs);
    const double edge = LeadingEdge(response, fs);
    RoomOptions o;
    o.response = response;
    o.noise = RoomOptions::Noise::kWhite;
    o.snr_db = request.snr_db;
    o.seed = request.seed + 11;
    const std::vector<float> heard = RenderRoom(clean.samples, fs, o);
    std::vector<RxEvent> events;
    const auto receiver = profile->MakeReceiver(ReceiverOptions{});
    receiver->Process(heard.data(), heard.size(), events);
    receiver->Flush(events);
    std::vector<double> errors;
    for (const RxEvent& e : events) {
      if (e.kind != RxEvent::Kind::kPacket || std::isnan(e.arrival)) continue;
      // The packet sent nearest before its arrival, and only if it carries the same data.
      const auto after = std::upper_bound(starts.begin(), starts.end(), e.arrival - edge + 0.05);
      if (after == starts.begin()) continue;
      const std::size_t p = static_cast<std::size_t>(after - starts.begin()) - 1;
      if (HexBytes(e.data) != clean.sent[p]) continue;
      errors.push_back(e.arrival - (starts[p] + edge));
    }
    const bool counts = room.figures.drr_db >= request.min_drr_db;
    if (counts) {
      counted.insert(counted.end(), errors.begin(), errors.end());
      ++counted_rooms;
      counted_sent += request.packets;
    }
    const double jitter = AbsQuantile(AgainstMedian(errors), 0.9);
    if (std::isfinite(jitter)) {
      jitters.push_back(jitter);
      if (jitter > worst_jitter) {
        worst_jitter = jitter;
        worst_jitter_room = room.name;
      }
    }
    std::printf("%-44s %+7.1f %6.2f %4zu/%-2d %10.1f %10.1f %10.1f %10.1f%s\n", room.name.c_str(), room.figures.drr_db,
                room.figures.rt60_s, errors.size(), request.packets, AbsQuantile(errors, 0.5) * 1e6,
                AbsQuantile(errors, 0.9) * 1e6, AbsQuantile(errors, 1.0) * 1e6, jitter * 1e6,
                counts ? "" : "  (below --min-drr)");
  }
  const double median = AbsQuantile(counted, 0.5), p90 = AbsQuantile(counted, 0.9);
  std::printf("rooms with DRR >= %+.1f dB: %d, packets timed %zu/%d, median %.1f us, p90 %.1f us\n", request.min_drr_db,
              counted_rooms, counted.size(), counted_sent, median * 1e6, p90 * 1e6);
  std::printf("target: median <= %.0f us and p90 <= %.0f us: %s\n", kTargetMedianS * 1e6, kTargetP90S * 1e6,
              median <= kTargetMedianS && p90 <= kTargetP90S ? "yes" : "NO");
  const auto over = std::count_if(jitters.begin(), jitters.end(), [](double j) { return j > kTargetJitterP90S; });
  std::printf("jitter against each room's own median (p90, every room timed): median over rooms %.1f us, worst %.1f us "
              "(%s); rooms over %.0f us: %td of %zu\n",
              AbsQuantile(jitters, 0.5) * 1e6, worst_jitter * 1e6, worst_jitter_room.empty() ? "none" : worst_jitter_room.c_str(),
              kTargetJitterP90S * 1e6, over, jitters.size());
  std::printf("target: jitter p90 <= %.0f us in every room: %s\n", kTargetJitterP90S * 1e6,
              !jitters.empty() && over == 0 ? "yes" : "NO");
  if (!request.errors_out.empty()) {
    if (counted.size() < 2) {
      std::fprintf(stderr, "nava_bench: --errors-out %s: only %zu packets timed, expected at least 2\n",
                   request.errors_out.c_str(), counted.size());
      return 1;
    }
    WriteErrors(request, counted, counted_rooms, counted_sent);
    std::printf("wrote %s\n", request.errors_out.c_str());
  }
  return 0;
}

}  // namespace nava_modem::tools
