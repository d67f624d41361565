#pragma once

#include <cstdint>

namespace local_mutex {

// The timers of the thesis's chapter 7 (its simulation values are the defaults). They run on
// the robot's clock (simulated time in simulation), never on the Lamport clock.
struct MutexOptions {
  int robot_id = 1;              // 1..255, unique among robots that can hear each other
  double grab_time = 40.0;       // s of silence while WANTED before taking the lock (t_grab)
  double request_mean = 15.0;    // s between requests (t_request), Gaussian
  double request_sd = 2.0;
  double lock_mean = 10.0;       // s between lock announcements while HELD (t_lock), Gaussian
  double lock_sd = 1.0;
  // A packet carrying our own id that repeats what we sent this recently is our own echo, not
  // a second robot with our id.
  double echo_window = 2.0;
  std::uint32_t seed = 1;        // for the Gaussian intervals
};

// Throws std::invalid_argument naming the option and what was expected: an id outside 1..255,
// t_grab <= 0, t_lock >= t_grab (a holder must announce before a waiting robot's timer runs
// out), t_request >= t_grab (a robot would take the lock without ever asking), negative
// deviations.
void ValidateMutexOptions(const MutexOptions& options);

}  // namespace local_mutex
