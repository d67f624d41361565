#include "local_mutex/mutex_options.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace local_mutex {
namespace {

void Require(bool ok, const std::string& name, double value, const std::string& expected) {
  if (ok) return;
  std::ostringstream text;
  text << "local_mutex: " << name << " = " << value << ": expected " << expected;
  throw std::invalid_argument(text.str());
}

bool Finite(double x) { return std::isfinite(x); }

}  // namespace

void ValidateMutexOptions(const MutexOptions& o) {
  Require(o.robot_id >= 1 && o.robot_id <= 255, "robot_id", o.robot_id, "an integer in 1..255");
  Require(Finite(o.grab_time) && o.grab_time > 0.0, "grab_time", o.grab_time, "> 0 s");
  Require(Finite(o.request_mean) && o.request_mean > 0.0 && o.request_mean < o.grab_time, "request_mean",
          o.request_mean, "> 0 s and shorter than grab_time (" + std::to_string(o.grab_time) + " s)");
  Require(Finite(o.lock_mean) && o.lock_mean > 0.0 && o.lock_mean < o.grab_time, "lock_mean", o.lock_mean,
          "> 0 s and shorter than grab_time (" + std::to_string(o.grab_time) + " s)");
  Require(Finite(o.request_sd) && o.request_sd >= 0.0, "request_sd", o.request_sd, ">= 0 s");
  Require(Finite(o.lock_sd) && o.lock_sd >= 0.0, "lock_sd", o.lock_sd, ">= 0 s");
  Require(Finite(o.echo_window) && o.echo_window >= 0.0, "echo_window", o.echo_window, ">= 0 s");
}

}  // namespace local_mutex
