#pragma once

// The thesis's failure bound (section 6.3.2): a robot that sends n requests before taking the
// lock fails only if every one of them is lost to a robot in earshot, which happens with
// probability (p_r)^n when each is lost independently with probability p_r; so
// n = log_{p_r}(rho) requests keep the failure under rho. What local_mutex_sim --bound measures
// it with. No ROS.
#include <cstdint>

#include "local_mutex/mutex_options.h"
#include "local_mutex/team_sim.h"

namespace local_mutex {

// A measured rate with its 95 % confidence interval (Wilson's score interval, which stays
// inside [0, 1] and is not empty at 0 events, where the normal approximation is).
struct Proportion {
  double rate = 0.0, low = 0.0, high = 1.0;
};
// `events` of `trials`; with no trials, rate 0 in [0, 1]. Throws std::invalid_argument when
// events exceed trials.
Proportion WilsonInterval(std::uint64_t events, std::uint64_t trials);

// p_r: the share of request copies that did not reach a robot in range whole (0 with none
// offered).
double RequestLoss(const RequestCopies& copies);
// q_r: the share that did not reach it at all, not even as noise (0 with none offered).
double RequestSilence(const RequestCopies& copies);

// The fewest requests n >= 1 for which p^n <= rho: 1 when p is 0; 0 when no n does (p of 1).
// Throws std::invalid_argument for a p outside [0, 1] or a rho outside (0, 1).
int RequestsFor(double rho, double p);

// The timers with `n` requests fitting in one t_grab of silence: the requests go out every
// t_grab / (n + 0.5) s (sd 2/15 of that, as the thesis's 15 +- 2 s), and the holder announces
// at least as often. Throws std::invalid_argument for n < 1.
MutexOptions WithRequestsPerGrab(const MutexOptions& base, int n);

}  // namespace local_mutex
