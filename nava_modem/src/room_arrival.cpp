#include "nava_modem/room_arrival.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace nava_modem {
namespace {

// The direct sound is looked for from kDirectBeforeStrongestS before a chirp's strongest peak
// (it may precede a stronger reflection) to this long after it, with kFloorLeadS before that for
// the floor.
constexpr double kArrivalBefore = kDirectBeforeStrongestS + kFloorLeadS, kArrivalAfter = 0.010;

}  // namespace

RoomArrival::RoomArrival(const std::vector<float>& chirp, double sample_rate)
    : sample_rate_(sample_rate),
      timer_(chirp, chirp.size() + static_cast<std::size_t>(std::lround((kArrivalBefore + kArrivalAfter) * sample_rate)),
             sample_rate) {}

double RoomArrival::Time(const SampleRing& heard, double pre, std::optional<double> post) {
  const double fs = sample_rate_;
  const std::size_t count = timer_.count();
  // Each chirp's window, from kArrivalBefore before it (its samples, and where its chirp lies in
  // it); the second chirp lies where the decode put it, to a fraction of a sample, so the two
  // responses add up in phase.
  std::array<std::vector<float>, 2> cut;
  std::array<double, 2> from{}, at{};
  std::array<std::size_t, 2> lead{};
  const std::array<double, 2> chirps = {pre, post.value_or(0.0)};
  const std::size_t windows = post ? 2 : 1;
  for (std::size_t w = 0; w < windows; ++w) {
    const double start = std::floor(chirps[w] - kArrivalBefore * fs);
    const std::int64_t first = std::max<std::int64_t>(0, static_cast<std::int64_t>(start));
    cut[w].resize(count);
    // (Nothing past what has been heard: a packet decoded at the stream's end.)
    for (std::size_t k = 0; k < count; ++k) {
      const std::int64_t n = first + static_cast<std::int64_t>(k);
      cut[w][k] = n < heard.count() ? heard[n] : 0.0f;
    }
    from[w] = static_cast<double>(first);
    at[w] = chirps[w] - from[w];
    // Near the stream's start a window begins later: its lead is what is left, and with less
    // than a quarter of it left its floor is read over the whole search.
    const double left = std::round(kFloorLeadS * fs - (from[w] - start));
    lead[w] = left >= 0.25 * kFloorLeadS * fs ? static_cast<std::size_t>(left) : 0;
  }
  if (!post) return from[0] / fs + timer_.Together({{cut[0].data(), 0.0, lead[0]}});
  return from[0] / fs + timer_.Together({{cut[0].data(), 0.0, lead[0]}, {cut[1].data(), at[1] - at[0], lead[1]}});
}

}  // namespace nava_modem
