#include "local_mutex/failure_bound.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace local_mutex {

Proportion WilsonInterval(std::uint64_t events, std::uint64_t trials) {
  if (events > trials) {
    throw std::invalid_argument("Wilson interval: " + std::to_string(events) + " events in " + std::to_string(trials) +
                                " trials: expected no more events than trials");
  }
  if (trials == 0) return {};
  constexpr double z = 1.959963984540054;  // two-sided 95 %
  const double n = static_cast<double>(trials), p = static_cast<double>(events) / n;
  const double centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
  const double half = z / (1.0 + z * z / n) * std::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n));
  // At 0 (or all) events the interval's end is exactly 0 (or 1); rounding leaves a hair.
  return {p, events == 0 ? 0.0 : std::max(0.0, centre - half), events == trials ? 1.0 : std::min(1.0, centre + half)};
}

namespace {
double MissedShare(std::uint64_t reached, std::uint64_t offered) {
  if (offered == 0) return 0.0;
  return 1.0 - static_cast<double>(std::min(reached, offered)) / static_cast<double>(offered);
}
}  // namespace

double RequestLoss(const RequestCopies& copies) { return MissedShare(copies.heard, copies.offered); }

double RequestSilence(const RequestCopies& copies) { return MissedShare(copies.sounded, copies.offered); }

int RequestsFor(double rho, double p) {
  if (!(p >= 0.0 && p <= 1.0)) throw std::invalid_argument("requests for a bound: p_r = " + std::to_string(p) + ": expected [0, 1]");
  if (!(rho > 0.0 && rho < 1.0)) throw std::invalid_argument("requests for a bound: rho = " + std::to_string(rho) + ": expected (0, 1)");
  if (p == 0.0) return 1;
  if (p >= 1.0) return 0;
  // The smallest n with n log p <= log rho; the product checked directly against rounding.
  int n = std::max(1, static_cast<int>(std::ceil(std::log(rho) / std::log(p) - 1e-9)));
  while (std::pow(p, n) > rho * (1.0 + 1e-12)) ++n;  // 0.1^3 is a hair over 1e-3 in doubles
  return n;
}

MutexOptions WithRequestsPerGrab(const MutexOptions& base, int n) {
  if (n < 1) throw std::invalid_argument("requests per t_grab: " + std::to_string(n) + ": expected at least 1");
  MutexOptions o = base;
  // n requests fit in one t_grab of silence: at t_request, 2 t_request, ... n t_request.
  o.request_mean = base.grab_time / (n + 0.5);
  o.request_sd = o.request_mean * 2.0 / 15.0;
  o.lock_mean = std::min(base.lock_mean, o.request_mean);
  o.lock_sd = o.lock_mean * 0.1;
  return o;
}

}  // namespace local_mutex
