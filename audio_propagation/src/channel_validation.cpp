#include "audio_propagation/channel_validation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include "audio_propagation/decode_table.h"
#include "grid/option_checks.h"
#include "nava_modem/frame.h"
#include "nava_modem/modem_options.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_channel.h"
#include "world_sim/collision.h"

namespace audio_propagation {
namespace {

// The tools' carrier threshold (nava_decode --threshold-db, the decode tables' receiver), dB of
// full scale.
constexpr double kCarrierThresholdDb = -40.0;
// After each packet: its room's tail and a gap (before the first: the noise's lead, in Judge).
constexpr double kGapS = 0.4;
constexpr int kDrawTries = 1000000;

// The longest reverberation anywhere in the world.
double LongestRt60(const world_sim::Acoustics& a) {
  double rt60 = a.room.rt60;
  for (const world_sim::AcousticRegion& r : a.regions) rt60 = std::max(rt60, r.room.rt60);
  return rt60;
}

// The time the noise sources' duty cycles are drawn over: their longest period (any moment of
// a cycle is as likely), or 1 s without sources.
double LongestPeriod(const world_sim::Acoustics& a) {
  double period = 1.0;
  for (const world_sim::NoiseSourceSpec& s : a.noise_sources) period = std::max(period, s.period);
  return period;
}

// One link's judge: its own model, renderer and receiver profile (none of them is shared
// between threads).
class LinkJudge {
 public:
  LinkJudge(const PropagationModel& propagation, const world_sim::Acoustics& acoustics, const DecodeTable& table,
            const std::vector<std::string>& team, const std::vector<Eigen::Vector2d>& resting,
            const ValidationOptions& options)
      : model_(propagation, acoustics, table, team),
        team_(team),
        resting_(resting),
        options_(options),
        spacing_(nava_modem::ProfileAirtime(options.profile) + 1.2 * LongestRt60(acoustics) + kGapS) {
    nava_modem::ModemOptions modem;
    modem.sample_rate = options.sample_rate;
    profile_ = nava_modem::MakeProfile(options.profile, modem);
  }

  void Judge(ValidationLink& link, std::uint32_t seed) const {
    std::mt19937 rng(seed);
    Scene scene;
    scene.profile = options_.profile;
    // The receiver hears the noise for as long as the tables give it before a packet, and before
    // that for as long as it remembers: a whine that started then is new to it, as on a robot.
    const double lead = kTableLeadSeconds + nava_modem::WhineSettleSeconds(options_.profile);
    scene.start = link.time - lead;
    const double longest_travel = 2.0 * link.path_length / model_.propagation().options().speed_of_sound;
    scene.duration = lead + options_.packets * spacing_ + longest_travel;
    scene.robots = {{kValidationSender, {{link.time, link.sender.x(), link.sender.y(), 0.0}}},
                    {kValidationListener, {{link.time, link.listener.x(), link.listener.y(), 0.0}}}};
    std::set<std::array<std::uint8_t, 4>> sent;
    for (int k = 0; k < options_.packets; ++k) {
      ScenePacket p;
      p.time = link.time + k * spacing_;
      p.sender = kValidationSender;
      do {
        for (auto& b : p.data) b = static_cast<std::uint8_t>(rng() & 0xff);
      } while (!sent.insert(p.data).second);
      scene.packets.push_back(p);
    }
    std::vector<bool> decoded(scene.packets.size(), false);
    SceneRenderOptions render;
    render.sample_rate = options_.sample_rate;
    render.seed = static_cast<std::uint32_t>(rng());
    render.speech = options_.speech;
    render.measured_rooms = options_.measured_rooms;
    const SceneRenderer renderer(model_, team_, resting_, std::move(render));
    const SceneRendering r = renderer.Render(scene, {kValidationListener});

    link.packets = options_.packets;
    double probability = 0.0;
    for (std::size_t k = 0; k < r.hearings.size(); ++k) {
      const PacketHearing& h = r.hearings[k];
      if (k == 0) link.prediction = h.prediction;
      if (!h.reachable) continue;
      JudgedPacket j;
      j.probability = h.prediction.probability;
      j.snr_db = h.prediction.snr_db;
      j.kind = h.prediction.kind;
      j.noise_gap_db = h.in_scene && h.noise_power > 0.0
                           ? 10.0 * std::log10(h.noise_power) + kReferenceDb - h.model_noise_db
                           : std::numeric_limits<double>::quiet_NaN();
      probability += j.probability;
      link.judged.push_back(j);
    }
    link.model = probability / options_.packets;

    // The receiver hears the recording at the decode tables' scale: its peak at 0.9 of full scale.
    std::vector<float> heard = r.listeners.at(0).Mix();
    float peak = 0.0f;
    for (float v : heard) peak = std::max(peak, std::fabs(v));
    if (peak > 0.0f) {
      for (float& v : heard) v *= static_cast<float>(nava_modem::kRoomPeak) / peak;
    }
    nava_modem::ReceiverOptions rx;
    rx.carrier_threshold_db = kCarrierThresholdDb;
    const auto receiver = profile_->MakeReceiver(rx);
    std::vector<nava_modem::RxEvent> events;
    receiver->Process(heard.data(), heard.size(), events);
    receiver->Flush(events);
    link.decoded = 0;
    for (const nava_modem::RxEvent& e : events) {
      if (e.kind != nava_modem::RxEvent::Kind::kPacket) continue;
      for (std::size_t k = 0; k < scene.packets.size(); ++k) {
        const ScenePacket& p = scene.packets[k];
        // Each packet counts once (their data differ).
        if (e.data != std::vector<std::uint8_t>(p.data.begin(), p.data.end()) || decoded[k]) continue;
        decoded[k] = true;
        ++link.decoded;
        // A link stands still: all its packets have a path, or none.
        if (k < link.judged.size()) link.judged[k].decoded = true;
      }
    }
  }

  const AcousticModel& model() const { return model_; }

 private:
  AcousticModel model_;
  std::vector<std::string> team_;
  std::vector<Eigen::Vector2d> resting_;
  ValidationOptions options_;
  double spacing_;
  std::unique_ptr<nava_modem::ModemProfile> profile_;
};

}  // namespace

PropagationOptions ValidationPropagation(double map_span, int threads) {
  PropagationOptions o;
  // A path round a building is shorter than twice its width plus height.
  const double reach = std::max(2.0 * map_span, 1.0);
  o.threshold_db = o.source_level_db - 20.0 * std::log10(reach / o.reference_distance);
  o.threads = threads;
  return o;
}

FreePoints::FreePoints(const grid::OccupancyMap& map, double clearance, const Eigen::Vector2d* seed)
    : map_(map), clearance_(clearance) {
  std::vector<bool> reached(static_cast<std::size_t>(map.width()) * map.height(), false);
  auto index = [&](int i, int j) { return static_cast<std::size_t>(j) * map.width() + i; };
  if (seed) {
    // The free space connected to the seed (4-neighbours).
    const Eigen::Vector2i s = map.WorldToCell(*seed);
    if (map.Blocks(s.x(), s.y())) throw std::runtime_error("free points: the seed point is not in free space");
    std::deque<Eigen::Vector2i> open{s};
    reached[index(s.x(), s.y())] = true;
    while (!open.empty()) {
      const Eigen::Vector2i c = open.front();
      open.pop_front();
      for (const Eigen::Vector2i& d : {Eigen::Vector2i(1, 0), Eigen::Vector2i(-1, 0), Eigen::Vector2i(0, 1), Eigen::Vector2i(0, -1)}) {
        const Eigen::Vector2i n = c + d;
        if (map.Blocks(n.x(), n.y()) || reached[index(n.x(), n.y())]) continue;
        reached[index(n.x(), n.y())] = true;
        open.push_back(n);
      }
    }
  }
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      // Points too near a wall are turned away by Draw.
      if (!map.Blocks(i, j) && (!seed || reached[index(i, j)])) cells_.emplace_back(i, j);
    }
  }
}

Eigen::Vector2d FreePoints::Draw(std::mt19937& rng) const {
  if (cells_.empty()) throw std::runtime_error("free points: no free point far enough from walls");
  std::uniform_int_distribution<std::size_t> pick(0, cells_.size() - 1);
  std::uniform_real_distribution<double> within(-0.5, 0.5);
  for (int tries = 0; tries < kDrawTries; ++tries) {
    const Eigen::Vector2i c = cells_[pick(rng)];
    const Eigen::Vector2d p = map_.CellCenter(c.x(), c.y()) + map_.resolution() * Eigen::Vector2d(within(rng), within(rng));
    if (!world_sim::DiscHitsWalls(map_, p, clearance_)) return p;
  }
  throw std::runtime_error("free points: no free point far enough from walls");
}

void ValidateOptions(const ValidationOptions& o) {
  grid::RequireAtLeast("validation links", o.links, 1);
  grid::RequireAtLeast("validation packets", o.packets, 1);
  grid::RequireAtLeast("validation threads", o.threads, 1);
  grid::RequireAtLeast("validation clearance (m)", o.clearance, 0.0);
  grid::RequireAtLeast("validation min_separation (m)", o.min_separation, 0.0);
  grid::RequireAtLeast("validation channel_hearing_distance (m)", o.channel_hearing_distance, 0.0);
  nava_modem::ValidateSampleRate("validation sample rate", o.sample_rate);
}

std::vector<ValidationLink> ValidateLinks(const PropagationModel& propagation, const world_sim::Acoustics& acoustics,
                                          const DecodeTable& table, const std::vector<std::string>& world_robots,
                                          const std::vector<Eigen::Vector2d>& resting, const ValidationOptions& options,
                                          const std::function<void(int)>& progress) {
  ValidateOptions(options);
  if (world_robots.size() != resting.size()) throw std::invalid_argument("validation: a resting place per robot");
  std::vector<std::string> team = world_robots;
  team.push_back(kValidationSender);
  team.push_back(kValidationListener);
  std::vector<Eigen::Vector2d> rest = resting;
  // Until a link places them, the two stand at the first point drawn (they are always placed).
  const grid::OccupancyMap& map = propagation.map();
  const FreePoints points(map, options.clearance, resting.empty() ? nullptr : &resting.front());

  // The links, drawn one after another from one generator: the same seed gives the same links.
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> when(0.0, LongestPeriod(acoustics));
  std::vector<ValidationLink> links(static_cast<std::size_t>(options.links));
  std::vector<std::uint32_t> seeds(links.size());
  for (std::size_t k = 0; k < links.size(); ++k) {
    ValidationLink& l = links[k];
    do {
      l.sender = points.Draw(rng);
      l.listener = points.Draw(rng);
    } while ((l.sender - l.listener).norm() < options.min_separation);
    l.time = when(rng);
    seeds[k] = static_cast<std::uint32_t>(rng());
    const SoundPath path = propagation.Path(l.sender, l.listener);
    l.reachable = path.reachable;
    l.path_length = path.reachable ? path.length : std::numeric_limits<double>::infinity();
    l.corners = path.bends;
    l.beyond_hearing = options.channel_hearing_distance > 0.0 && l.path_length > options.channel_hearing_distance;
  }
  rest.push_back(links.front().sender);
  rest.push_back(links.front().listener);

  std::atomic<std::size_t> next{0};
  std::atomic<int> done{0};
  std::mutex report;
  std::exception_ptr failure;
  auto work = [&] {
    try {
      const LinkJudge judge(propagation, acoustics, table, team, rest, options);
      for (std::size_t k = next++; k < links.size(); k = next++) {
        judge.Judge(links[k], seeds[k]);
        const int n = ++done;
        if (progress) {
          const std::lock_guard<std::mutex> lock(report);
          progress(n);
        }
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(report);
      if (!failure) failure = std::current_exception();
      next = links.size();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < options.threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return links;
}

namespace {

// A bin while links are added: sums, not yet shares.
struct BinSums {
  DistanceBin bin;  // model and rendered hold packets, mean_length the sum of lengths
  double packets = 0.0;
  int measured = 0;  // links with a length
  void Take(const BinSums& next) {
    bin.high = next.bin.high;
    bin.links += next.bin.links;
    bin.mean_length += next.bin.mean_length;
    bin.model += next.bin.model;
    bin.rendered += next.bin.rendered;
    packets += next.packets;
    measured += next.measured;
  }
};

}  // namespace

std::vector<DistanceBin> BinByLength(const std::vector<ValidationLink>& links, const std::vector<double>& edges,
                                     int min_links) {
  if (edges.empty()) throw std::invalid_argument("distance bins: no edges");
  std::vector<BinSums> raw(edges.size());
  for (std::size_t b = 0; b < edges.size(); ++b) {
    raw[b].bin.low = edges[b];
    raw[b].bin.high = b + 1 < edges.size() ? edges[b + 1] : std::numeric_limits<double>::infinity();
  }
  for (const ValidationLink& l : links) {
    const std::size_t above = static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), l.path_length) - edges.begin());
    BinSums& b = raw[above == 0 ? 0 : above - 1];
    ++b.bin.links;
    if (std::isfinite(l.path_length)) {
      b.bin.mean_length += l.path_length;
      ++b.measured;
    }
    b.bin.model += l.model * l.packets;
    b.bin.rendered += l.decoded;
    b.packets += l.packets;
  }
  // Left to right, a bin takes in the next ones until it holds enough links; a short last one
  // goes to the one before.
  std::vector<BinSums> merged;
  for (const BinSums& b : raw) {
    if (b.bin.links == 0) continue;
    if (!merged.empty() && merged.back().bin.links < min_links) {
      merged.back().Take(b);
    } else {
      merged.push_back(b);
    }
  }
  if (merged.size() > 1 && merged.back().bin.links < min_links) {
    const BinSums tail = merged.back();
    merged.pop_back();
    merged.back().Take(tail);
  }
  std::vector<DistanceBin> bins;
  for (const BinSums& m : merged) {
    DistanceBin b = m.bin;
    b.mean_length = m.measured ? b.mean_length / m.measured : 0.0;
    b.model = 100.0 * b.model / m.packets;
    b.rendered = 100.0 * b.rendered / m.packets;
    bins.push_back(b);
  }
  return bins;
}

double Agreement(const std::vector<DistanceBin>& bins) {
  double worst = 0.0;
  for (const DistanceBin& b : bins) worst = std::max(worst, std::fabs(b.model - b.rendered));
  return worst;
}

}  // namespace audio_propagation
