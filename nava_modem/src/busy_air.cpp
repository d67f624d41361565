#include "nava_modem/busy_air.h"

#include <cmath>

namespace nava_modem {

void BusyAir::SetThreshold(std::optional<double> db) {
  threshold_power_.reset();
  if (db) threshold_power_ = std::pow(10.0, *db / 10.0);
}

void BusyAir::Step(double time, double power, double quality, bool waiting, std::vector<RxEvent>& events) {
  if (!threshold_power_) return;
  const bool loud = power >= *threshold_power_;
  if (loud) {
    if (!busy_) {
      busy_ = true;
      had_frame_ = false;
      start_ = time;
      power_sum_ = quality_sum_ = 0.0;
      steps_ = 0;
    }
    last_loud_ = time;
  }
  if (!busy_) return;
  power_sum_ += power;
  quality_sum_ += quality;
  ++steps_;
  if (time - last_loud_ <= release_ || waiting) return;
  if (!had_frame_ && last_loud_ - start_ >= min_) {
    RxEvent ev;
    ev.kind = RxEvent::Kind::kNoise;
    ev.noise = RxEvent::Noise::kZeroByte;
    ev.start = start_;
    ev.end = last_loud_;
    ev.level_db = 10.0 * std::log10(power_sum_ / steps_ + 1e-20);
    ev.quality = quality_sum_ / steps_;
    events.push_back(ev);
  }
  busy_ = false;
}

}  // namespace nava_modem
