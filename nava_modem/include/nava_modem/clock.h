#pragma once

#include <chrono>
#include <thread>

namespace nava_modem {

// Wall time for what the audio cannot pace: waiting to reopen a failed device. Tests give a
// link a clock of their own, so that waits take no time and can be checked.
class Clock {
 public:
  virtual ~Clock() = default;
  virtual double Now() = 0;  // s, from any fixed origin
  virtual void Sleep(double seconds) = 0;
};

class SteadyClock : public Clock {
 public:
  double Now() override { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
  void Sleep(double seconds) override { std::this_thread::sleep_for(std::chrono::duration<double>(seconds)); }
  static SteadyClock& Instance() {
    static SteadyClock clock;
    return clock;
  }
};

}  // namespace nava_modem
