#include "nava_modem/array_decode.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <stdexcept>
#include <string>

#include "nava_modem/room_phy.h"

namespace nava_modem {
namespace {

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

DirectionOptions DirectionOptionsFor(Profile profile, const ModemOptions& modem, std::vector<Microphone2D> mics) {
  DirectionOptions o;
  o.mics = std::move(mics);
  o.sample_rate = modem.sample_rate;
  if (profile == Profile::kRoom) {
    o.low_hz = room_phy::kChirpLowHz;
    o.high_hz = room_phy::kChirpHighHz;
    o.max_seconds = room_phy::kChirpSeconds;
  } else {
    // The FSK's energy lies within about two bit rates of its tones.
    o.low_hz = std::max(0.0, std::min(modem.mark_hz, modem.space_hz) - 2.0 * modem.baud);
    o.high_hz = std::max(modem.mark_hz, modem.space_hz) + 2.0 * modem.baud;
    o.max_seconds = ProfileAirtime(profile, modem);
  }
  o.high_hz = std::min(o.high_hz, modem.sample_rate / 2.0);
  return o;
}

std::size_t LoudestChannel(const std::vector<std::vector<float>>& channels) {
  std::size_t best = 0;
  double loudest = -1.0;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    double energy = 0.0;
    for (float v : channels[c]) energy += static_cast<double>(v) * v;
    if (energy > loudest) {
      loudest = energy;
      best = c;
    }
  }
  return best;
}

std::vector<RxEvent> DecodeArray(const ModemProfile& profile, const ReceiverOptions& options,
                                 const std::vector<std::vector<float>>& channels, const std::vector<Microphone2D>& mics,
                                 double* estimate_seconds) {
  if (channels.empty()) throw std::invalid_argument("no audio channels to decode");
  for (const std::vector<float>& c : channels) {
    if (c.size() != channels[0].size()) throw std::invalid_argument("audio channels of different lengths");
  }
  if (mics.size() >= 2 && mics.size() != channels.size()) {
    throw std::invalid_argument(std::to_string(channels.size()) + " audio channels, but " + std::to_string(mics.size()) +
                                " microphone positions (one per channel)");
  }
  const auto receiver = profile.MakeReceiver(options);
  std::vector<RxEvent> events;
  const std::vector<float>& heard = channels[LoudestChannel(channels)];
  receiver->Process(heard.data(), heard.size(), events);
  receiver->Flush(events);
  if (estimate_seconds) *estimate_seconds = 0.0;
  if (mics.size() < 2) return events;

  const double rate = profile.options().sample_rate;
  const DirectionEstimator estimator(DirectionOptionsFor(profile.profile(), profile.options(), mics));
  const std::int64_t length = static_cast<std::int64_t>(channels[0].size());
  const double started = CpuSeconds();
  for (RxEvent& e : events) {
    const std::int64_t from = std::clamp<std::int64_t>(std::llround(e.start * rate), 0, length);
    const std::int64_t to = std::clamp<std::int64_t>(std::llround(e.end * rate), from, length);
    if (to - from < 64) continue;  // too little of it to tell
    std::vector<const float*> spans;
    for (const std::vector<float>& c : channels) spans.push_back(c.data() + from);
    const Direction direction = estimator.Estimate(spans, static_cast<std::size_t>(to - from));
    e.direction = direction.bearing;
    e.direction_confidence = std::isfinite(direction.bearing) ? direction.confidence : 0.0;
  }
  if (estimate_seconds) *estimate_seconds = CpuSeconds() - started;
  return events;
}

}  // namespace nava_modem
