#include "table_cells.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "bench_support/speech.h"
#include "nava_modem/frame.h"
#include "nava_modem/packet_receiver.h"
#include "nava_modem/room_channel.h"

namespace audio_propagation::tools {
namespace {

using namespace nava_modem;
using bench_support::SpeechFrom;

constexpr double kQuietSeconds = 0.3;   // after each packet (besides the room's tail)
constexpr double kMaxOffset = 0.9;      // packet lengths the interferer may start before or after
constexpr double kFloorBelowDb = 20.0;  // the white floor under the disturbance
constexpr double kFloorSnrDb = 40.0;    // and under the signal, at least

std::vector<std::uint8_t> RandomData(std::mt19937& rng) {
  std::vector<std::uint8_t> data(kDataBytes);
  for (auto& b : data) b = static_cast<std::uint8_t>(rng() & 0xff);
  return data;
}

// `burst` at `start` in `length` samples of silence.
std::vector<float> Placed(const std::vector<float>& burst, std::size_t start, std::size_t length) {
  std::vector<float> out(length, 0.0f);
  std::copy(burst.begin(), burst.end(), out.begin() + static_cast<std::ptrdiff_t>(start));
  return out;
}

// The recording of one wanted packet (starting at sample `start`) under the cell's disturbance;
// `other_burst` is the other packet of the packet kind.
std::vector<float> Recording(const CellSetup& s, Interference kind, double rt60, double drr_db, double snr_db,
                             const std::vector<float>& burst, const std::vector<float>& other_burst, std::size_t start,
                             std::size_t length, std::mt19937& rng) {
  const double rate = s.modem.sample_rate;
  RoomOptions room;
  if (s.moved) {
    room.response = *s.moved->Draw(rt60, drr_db, static_cast<std::uint32_t>(rng())).response;
    room.model = RoomOptions::Model::kMeasured;
  } else if (s.response.empty()) {
    room.rt60 = rt60;
    room.drr_db = drr_db;
    room.model = s.model;
  } else {
    room.response = s.response;
  }
  room.seed = static_cast<std::uint32_t>(rng());
  room.noise = RoomOptions::Noise::kWhite;
  room.snr_db = std::max(kFloorSnrDb, snr_db + kFloorBelowDb);
  std::vector<float> talk;
  switch (kind) {
    case Interference::kWhite: room.snr_db = snr_db; break;
    case Interference::kPink:
      room.noise = RoomOptions::Noise::kPink;
      room.snr_db = snr_db;
      break;
    case Interference::kSpeech:
      room.sir_db = snr_db;
      talk = SpeechFrom(s.speech, static_cast<std::size_t>(rng()));
      break;
    case Interference::kWhine:
      room.whine_hz = s.table.whine_hz;
      room.whine_sir_db = snr_db;
      break;
    case Interference::kPacket: break;
  }
  RoomRenderInfo wanted_info;
  std::vector<float> heard = RenderRoom(Placed(burst, start, length), rate, room, talk, &wanted_info);
  if (kind != Interference::kPacket) return heard;

  // The other packet: its own room of the same rt60 and DRR, no noise of its own, starting
  // anywhere within kMaxOffset packet lengths of the wanted one (uniform, from the engine's bits:
  // the library's distributions differ between implementations).
  const double uniform = (static_cast<double>(rng()) + 0.5) / 4294967296.0;
  const double offset = kMaxOffset * static_cast<double>(burst.size()) * (2.0 * uniform - 1.0);
  RoomOptions other_room = room;
  other_room.noise = RoomOptions::Noise::kNone;
  other_room.seed = static_cast<std::uint32_t>(rng());
  if (s.moved) other_room.response = *s.moved->Draw(rt60, drr_db, static_cast<std::uint32_t>(rng())).response;
  RoomRenderInfo other_info;
  const std::vector<float> interferer =
      RenderRoom(Placed(other_burst, static_cast<std::size_t>(static_cast<double>(start) + offset), length), rate,
                 other_room, {}, &other_info);
  // Both back to the renderer's scale before its output gain, the other packet at its ratio,
  // and the sum to the renderer's peak again.
  const double other_gain = std::sqrt(wanted_info.signal_power / (other_info.signal_power * std::pow(10.0, snr_db / 10.0)));
  std::vector<double> mix(std::max(heard.size(), interferer.size()), 0.0);
  for (std::size_t i = 0; i < heard.size(); ++i) mix[i] = heard[i] / wanted_info.output_gain;
  for (std::size_t i = 0; i < interferer.size(); ++i) mix[i] += other_gain * interferer[i] / other_info.output_gain;
  double peak = 0.0;
  for (double v : mix) peak = std::max(peak, std::fabs(v));
  heard.resize(mix.size());
  for (std::size_t i = 0; i < mix.size(); ++i) heard[i] = static_cast<float>(kRoomPeak * mix[i] / peak);
  return heard;
}

// How the receiver's events judge the wanted packet (`data`), which sounded from `from` to `to`
// s; `other` is the interferer's data (empty: none). Counts packets never sent.
Heard Judge(const std::vector<RxEvent>& events, const std::vector<std::uint8_t>& data,
            const std::vector<std::uint8_t>& other, double from, double to, int* false_packets) {
  bool decoded = false, other_decoded = false;
  Heard noise = Heard::kNothing;  // the most telling noise so far: the enum runs up to kBadCrc
  for (const RxEvent& e : events) {
    if (e.kind == RxEvent::Kind::kPacket) {
      decoded = decoded || e.data == data;
      other_decoded = other_decoded || (!other.empty() && e.data == other);
      *false_packets += e.data != data && e.data != other;
      continue;
    }
    if (e.end < from || e.start > to) continue;
    const Heard h = e.noise == RxEvent::Noise::kBadCrc    ? Heard::kBadCrc
                    : e.noise == RxEvent::Noise::kOneByte ? Heard::kOneByte
                    : e.noise == RxEvent::Noise::kZeroByte ? Heard::kZeroByte
                                                           : Heard::kNothing;
    if (h != Heard::kNothing && (noise == Heard::kNothing || h > noise)) noise = h;
  }
  if (decoded) return Heard::kPacket;
  return other_decoded ? Heard::kNothing : noise;
}

}  // namespace

// One 32-bit seed from a few numbers (splitmix64's finaliser over them), so that every packet of
// every cell has its own rooms, noise and data whatever thread measures it.
std::uint32_t SeedOf(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d) {
  std::uint64_t x = 0x9e3779b97f4a7c15ull;
  for (std::uint64_t v : {a, b, c, d}) {
    x ^= v + 0x9e3779b97f4a7c15ull + (x << 6) + (x >> 2);
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    x ^= x >> 31;
  }
  return static_cast<std::uint32_t>(x);
}


CellCounts MeasureCell(const CellSetup& s, const ModemProfile& profile, std::size_t cell, Interference kind, double rt60,
                       double drr_db, double snr_db) {
  const double rate = s.modem.sample_rate;
  ReceiverOptions rx;
  rx.carrier_threshold_db = kToolCarrierThresholdDb;
  CellCounts counts;
  for (int p = 0; p < s.table.packets; ++p) {
    std::mt19937 rng(SeedOf(s.seed, cell, static_cast<std::uint64_t>(p), 0));
    const std::vector<std::uint8_t> data = RandomData(rng);
    const std::vector<float> burst = profile.ModulatePacket(data);
    const double offset = kind == Interference::kPacket ? kMaxOffset * burst.size() : 0.0;
    const std::size_t start = static_cast<std::size_t>(s.table.lead_s * rate + offset);
    const std::size_t length = start + burst.size() + static_cast<std::size_t>(kQuietSeconds * rate + offset);
    std::vector<std::uint8_t> other;
    std::vector<float> other_burst;
    if (kind == Interference::kPacket) {
      do {
        other = RandomData(rng);
      } while (other == data);
      other_burst = profile.ModulatePacket(other);
    }
    const std::vector<float> heard =
        Recording(s, kind, rt60, drr_db, snr_db, burst, other_burst, start, length, rng);
    const auto receiver = profile.MakeReceiver(rx);
    std::vector<RxEvent> events;
    receiver->Process(heard.data(), heard.size(), events);
    receiver->Flush(events);
    const Heard h = Judge(events, data, other, start / rate, (start + burst.size()) / rate, &counts.false_packets);
    ++counts.heard[static_cast<int>(h)];
  }
  return counts;
}


}  // namespace audio_propagation::tools
