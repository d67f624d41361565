#include "nava_modem/self_timer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "nava_modem/first_arrival.h"
#include "nava_modem/power_of_two.h"
#include "nava_modem/room_phy.h"

namespace nava_modem {
namespace {

// The search begins this long before the moment of sending (a clock read a block late).
constexpr double kLeadS = 0.02;
// The own sound counts as heard when its response stands this far above the search's median
// (FirstArrival's clarity): noise alone gives a few.
constexpr double kHeardClarity = 10.0;

}  // namespace

SelfTimer::SelfTimer(const ModemProfile& profile, double max_loop)
    : profile_(profile.profile()), rate_(profile.options().sample_rate), max_loop_(max_loop) {
  if (!(max_loop > 0.0 && max_loop <= 10.0)) {
    throw std::invalid_argument("self timer: longest loop " + std::to_string(max_loop) + " s: expected above 0 and at most 10");
  }
  // The room profile is timed on its first chirp, made for it; the nava profile's packet starts
  // with a steady tone that tells no time, so it is timed on all of its sound.
  if (profile_ == Profile::kRoom) chirp_ = room_phy::Chirp(rate_);
  const std::size_t size = PowerOfTwoAtLeast((profile.Airtime() * 1.1 + max_loop + 2.0 * kLeadS + 0.5) * rate_);
  ring_.assign(size, 0.0f);
  mask_ = size - 1;
}

void SelfTimer::Sent(std::vector<std::uint8_t> data, const std::vector<float>& burst, double sent) {
  Pending p;
  p.data = std::move(data);
  p.reference = chirp_.empty() ? burst : chirp_;
  p.from = std::llround((sent - kLeadS) * rate_);
  p.to = std::llround((sent + max_loop_ + kLeadS) * rate_) + static_cast<std::int64_t>(p.reference.size());
  pending_.push_back(std::move(p));
}

void SelfTimer::Heard(const float* samples, std::size_t count, std::vector<OwnTiming>& out) {
  for (std::size_t k = 0; k < count; ++k) ring_[static_cast<std::size_t>(n_ + static_cast<std::int64_t>(k)) & mask_] = samples[k];
  n_ += static_cast<std::int64_t>(count);
  Judge(out);
}

void SelfTimer::Skip(double seconds, std::vector<OwnTiming>& out) {
  for (Pending& p : pending_) out.push_back({std::move(p.data), std::numeric_limits<double>::quiet_NaN()});
  pending_.clear();
  const std::int64_t skipped = std::llround(seconds * rate_);
  for (std::int64_t k = 0; k < std::min<std::int64_t>(skipped, static_cast<std::int64_t>(ring_.size())); ++k) {
    ring_[static_cast<std::size_t>(n_ + k) & mask_] = 0.0f;
  }
  n_ += skipped;
}

void SelfTimer::Judge(std::vector<OwnTiming>& out) {
  while (!pending_.empty() && pending_.front().to <= n_) {
    Pending& p = pending_.front();
    const std::int64_t oldest = n_ - static_cast<std::int64_t>(ring_.size());
    const std::int64_t from = std::max({p.from, oldest, std::int64_t{0}});
    OwnTiming t{std::move(p.data), std::numeric_limits<double>::quiet_NaN()};
    if (p.to - from >= static_cast<std::int64_t>(p.reference.size())) {
      std::vector<float> heard(static_cast<std::size_t>(p.to - from));
      for (std::size_t k = 0; k < heard.size(); ++k) heard[k] = ring_[static_cast<std::size_t>(from + static_cast<std::int64_t>(k)) & mask_];
      double clarity = 0.0;
      const double edge = FirstArrival(heard.data(), heard.size(), p.reference, rate_, &clarity);
      if (clarity >= kHeardClarity) t.arrival = static_cast<double>(from) / rate_ + edge;
    }
    out.push_back(std::move(t));
    pending_.pop_front();
  }
}

}  // namespace nava_modem
