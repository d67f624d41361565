#include "ranging/simulated_ranging.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace ranging {
namespace {

// Sendings remembered for the receptions still to come: a packet lasts under 2 s and sound
// crosses 200 m in 0.6 s, so a few per robot is plenty.
constexpr std::size_t kSendingsPerRobot = 16;

}  // namespace

double ArrivalErrors::Draw(std::mt19937& rng) const {
  const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng) * static_cast<double>(quantiles.size() - 1);
  const std::size_t k = std::min(quantiles.size() - 2, static_cast<std::size_t>(u));
  const double f = u - static_cast<double>(k);
  return quantiles[k] + f * (quantiles[k + 1] - quantiles[k]);
}

void ValidateArrivalErrors(const ArrivalErrors& errors) {
  const auto& q = errors.quantiles;
  if (q.size() < 2) {
    throw std::invalid_argument("arrival errors: expected at least 2 quantiles, got " + std::to_string(q.size()));
  }
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (!std::isfinite(q[k]) || std::abs(q[k]) > 1.0) {
      throw std::invalid_argument("arrival errors: quantile " + std::to_string(k) + " = " + std::to_string(q[k]) +
                                  ": expected a finite error within 1 s");
    }
    if (k > 0 && q[k] < q[k - 1]) {
      throw std::invalid_argument("arrival errors: quantile " + std::to_string(k) + " = " + std::to_string(q[k]) +
                                  " is below the one before: expected them ascending");
    }
  }
}

void ValidateSimulatedRangingOptions(const SimulatedRangingOptions& o) {
  ValidateRangerOptions(o.ranger);
  ValidateArrivalErrors(o.errors);
  if (!(o.max_clock_rate_error >= 0.0 && o.max_clock_rate_error <= 0.001)) {
    throw std::invalid_argument("simulated ranging max_clock_rate_error " + std::to_string(o.max_clock_rate_error) +
                                ": expected 0 to 0.001");
  }
  if (!(o.rate_report_std <= 0.001)) {
    throw std::invalid_argument("simulated ranging rate_report_std " + std::to_string(o.rate_report_std) +
                                ": expected at most 0.001 (below 0: no rate reported)");
  }
}

SimulatedRanging::SimulatedRanging(std::vector<std::string> robots, const SimulatedRangingOptions& options)
    : robots_(std::move(robots)), options_(options), rng_(options.seed) {
  ValidateSimulatedRangingOptions(options_);
  if (robots_.empty()) throw std::invalid_argument("simulated ranging: expected at least one robot");
  std::uniform_real_distribution<double> rate(-options_.max_clock_rate_error, options_.max_clock_rate_error);
  // A sound card's clock starts when its node does: anywhere in the first quarter hour.
  std::uniform_real_distribution<double> offset(0.0, 900.0);
  for (const std::string& name : robots_) {
    rangers_.emplace_back(name, robots_, options_.ranger);
    const double r = rate(rng_);
    clocks_.push_back(SoundCard{r, offset(rng_)});
  }
}

double SimulatedRanging::Clock(std::size_t robot, double t) const {
  const SoundCard& c = clocks_.at(robot);
  return c.offset + (1.0 + c.rate_error) * t;
}

// What nava_modem's CardRateTracker needs before it gives a rate (its min_span), and how far
// off its rate then is (card_rate_test: within 3 to 5 ppm from reads through a sound server).
constexpr double kCardRateSpanS = 30.0;
constexpr double kCardRateStd = 3e-6;

void SimulatedRanging::TrackCardRate(std::size_t robot, double t) {
  SoundCard& card = clocks_.at(robot);
  if (card.rate_known) return;
  if (std::isnan(card.first_seen)) card.first_seen = t;
  if (t - card.first_seen < kCardRateSpanS) return;
  rangers_[robot].SetOwnRateError(card.rate_error + std::normal_distribution<double>(0.0, kCardRateStd)(rng_));
  card.rate_known = true;
}

void SimulatedRanging::Sent(std::size_t sender, const std::vector<std::uint8_t>& data, double start) {
  TrackCardRate(sender, start);
  Timing t;
  t.sender = t.listener = robots_.at(sender);
  t.data = data;
  t.arrival = Clock(sender, start) + options_.errors.Draw(rng_);
  t.stamp = start;
  rangers_[sender].Add(t);
  sendings_.push_back(Sending{sender, data, start, t});
  if (sendings_.size() > kSendingsPerRobot * robots_.size()) sendings_.pop_front();
}

bool SimulatedRanging::Heard(std::size_t listener, std::size_t sender, const std::vector<std::uint8_t>& data,
                             double path_length, double heard_at) {
  const auto sending = std::find_if(sendings_.rbegin(), sendings_.rend(), [&](const Sending& s) {
    return s.sender == sender && s.data == data && s.start <= heard_at;
  });
  if (sending == sendings_.rend() || listener == sender || !std::isfinite(path_length)) return false;
  const double arrival = sending->start + path_length / options_.ranger.speed_of_sound;
  TrackCardRate(listener, arrival);
  Timing t;
  t.sender = robots_.at(sender);
  t.listener = robots_.at(listener);
  t.data = data;
  t.arrival = Clock(listener, arrival) + options_.errors.Draw(rng_);
  if (options_.rate_report_std >= 0.0) {
    const double truth = (1.0 + clocks_[sender].rate_error) / (1.0 + clocks_[listener].rate_error) - 1.0;
    t.rate_error = truth + std::normal_distribution<double>(0.0, options_.rate_report_std)(rng_);
  }
  t.stamp = arrival;
  // The listener learns the sender's own timing of the packet as it hears it (on a real team
  // every robot gets every report; those of packets it never heard pair with nothing there).
  rangers_[listener].Add(sending->own);
  rangers_[listener].Add(t);
  rangers_[sender].Add(t);
  return true;
}

std::optional<Range> SimulatedRanging::RangeTo(std::size_t robot, std::size_t teammate, double now) const {
  return rangers_.at(robot).RangeTo(robots_.at(teammate), Clock(robot, now));
}

std::vector<Range> SimulatedRanging::Ranges(std::size_t robot, double now) const {
  return rangers_.at(robot).Ranges(Clock(robot, now));
}

Refused SimulatedRanging::refused() const {
  Refused sum;
  for (const TwoWayRanger& r : rangers_) {
    const Refused& x = r.refused();
    sum.unknown_robot += x.unknown_robot;
    sum.backwards += x.backwards;
    sum.bad_rate += x.bad_rate;
    sum.repeated_payload += x.repeated_payload;
    sum.implausible += x.implausible;
  }
  return sum;
}

}  // namespace ranging
