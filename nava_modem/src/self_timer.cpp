#include "nava_modem/self_timer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "nava_modem/first_arrival.h"
#include "nava_modem/power_of_two.h"
#include "nava_modem/timing_reference.h"

namespace nava_modem {
namespace {

// The wide search runs from the moment of sending to this long past the longest loop. It does
// not begin earlier: every packet of a profile begins with the same sound, and a teammate's
// packet (or the room profile's second chirp of one) that ended just before this send would be
// taken for it, as its sound comes first.
constexpr double kLeadS = 0.02;
// The own sound counts as heard when its response stands this far above the search's median
// (FirstArrival's clarity): noise alone gives 2 to 3, the own sound 9 or more (nava's reference,
// whose packet's other bits lift the median) to hundreds (the room chirp).
constexpr double kHeardClarity = 5.0;

// Once the loop's delay is known, the next packet is looked for only this far either side of it
// (a sound card's latency holds still while its streams run): a transform a tenth the size.
constexpr double kNarrowS = 0.02;
// The narrow search's sound counts where it is within this of the last loop (a loop drifts by a
// few samples between packets; nava's patterns repeat 2 bits, 6.7 ms, apart); elsewhere the
// packet is looked for over the whole loop. A sound found within kEdgeGuardS of the whole
// search's end may have been cut by it: it is not taken.
constexpr double kNarrowAgreeS = 0.003;
constexpr double kEdgeGuardS = 0.004;

double CheckedLoop(double max_loop) {
  if (!(max_loop > 0.0 && max_loop <= 10.0)) {
    throw std::invalid_argument("self timer: longest loop " + std::to_string(max_loop) + " s: expected above 0 and at most 10");
  }
  return max_loop;
}

}  // namespace

SelfTimer::SelfTimer(const ModemProfile& profile, double max_loop)
    : rate_(profile.options().sample_rate),
      max_loop_(CheckedLoop(max_loop)),
      reference_(PacketTimingReference(profile.profile(), profile.options())),
      wide_(reference_.sound, reference_.sound.size() + static_cast<std::size_t>(std::lround((max_loop_ + 2.0 * kLeadS) * rate_)), rate_),
      narrow_(reference_.sound, reference_.sound.size() + static_cast<std::size_t>(std::lround(2.0 * kNarrowS * rate_)), rate_) {
  const std::size_t size = PowerOfTwoAtLeast((profile.Airtime() * 1.1 + max_loop + 2.0 * kLeadS + 0.5) * rate_);
  ring_.assign(size, 0.0f);
  mask_ = size - 1;
}

void SelfTimer::Sent(std::vector<std::uint8_t> data, double sent) {
  Pending p;
  p.data = std::move(data);
  p.sent = sent;
  p.narrow = loop_.has_value();
  p.from = std::llround((sent + (p.narrow ? *loop_ - kNarrowS : 0.0)) * rate_ + reference_.offset);
  p.to = p.from + static_cast<std::int64_t>((p.narrow ? narrow_ : wide_).count());
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
  loop_.reset();  // the device reopened: its latency is new
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
    OwnTiming t{p.data, std::numeric_limits<double>::quiet_NaN()};
    if (p.from >= std::max<std::int64_t>(oldest, 0)) {  // all of its window still held
      ArrivalTimer& timer = p.narrow ? narrow_ : wide_;
      heard_.resize(timer.count());
      for (std::size_t k = 0; k < heard_.size(); ++k) heard_[k] = ring_[static_cast<std::size_t>(p.from + static_cast<std::int64_t>(k)) & mask_];
      double clarity = 0.0;
      const double edge = timer.Time(heard_.data(), &clarity);
      // Around the last loop the sound must be where that loop puts it: one that moved reaches
      // into the search cut, and nava's bit patterns match 2 and 4 bits off as well. Over the
      // whole loop it must lie inside the search, not reach in over its end.
      const double searched = static_cast<double>(timer.count() - reference_.sound.size()) / rate_;
      const bool inside = p.narrow ? std::abs(edge - kNarrowS) <= kNarrowAgreeS : edge <= searched - kEdgeGuardS;
      if (clarity >= kHeardClarity && inside) t.arrival = (static_cast<double>(p.from) - reference_.offset) / rate_ + edge;
    }
    if (std::isnan(t.arrival)) {
      // Not heard where the loop was (it moved: an underrun before the packet, a sound server
      // settling): this one is looked for over the whole of the loop, and so is the next.
      loop_.reset();
      if (p.narrow) {
        p.narrow = false;
        p.from = std::llround(p.sent * rate_ + reference_.offset);
        p.to = p.from + static_cast<std::int64_t>(wide_.count());
        continue;
      }
    } else {
      loop_ = t.arrival - p.sent;
    }
    out.push_back(std::move(t));
    pending_.pop_front();
  }
}

}  // namespace nava_modem
