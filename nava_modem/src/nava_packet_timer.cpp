#include "nava_modem/nava_packet_timer.h"

#include <cmath>
#include <limits>

#include "nava_modem/frame.h"
#include "nava_modem/measured_response.h"
#include "nava_modem/power_of_two.h"

namespace nava_modem {
namespace {

// A packet's first arrival is looked for from this long before the start the decoder placed (its
// filters' delay, and a direct sound before a stronger reflection) to this long after it.
constexpr double kArrivalBefore = 0.015, kArrivalAfter = 0.010;

}  // namespace

NavaPacketTimer::NavaPacketTimer(const ModemOptions& modem, double max_rate_error)
    : rate_(modem.sample_rate), reference_(PacketTimingReference(Profile::kNava, modem)) {
  if (modem.sample_rate >= 2.0 * kResponseBandHighHz) {
    timer_ = std::make_unique<ArrivalTimer>(
        reference_.sound, reference_.sound.size() + static_cast<std::size_t>(std::lround((kArrivalBefore + kArrivalAfter) * modem.sample_rate)),
        modem.sample_rate);
  }
  // A packet is reported well within a second of its end.
  const std::size_t size = PowerOfTwoAtLeast((kPacketBits / modem.baud * (1.0 + max_rate_error) + 1.5) * modem.sample_rate);
  raw_.assign(size, 0.0f);
  mask_ = size - 1;
}

double NavaPacketTimer::Time(double start) {
  if (!timer_) return std::numeric_limits<double>::quiet_NaN();
  const double fs = rate_;
  const std::int64_t from = std::llround((start - kArrivalBefore) * fs + reference_.offset);
  const std::size_t count = timer_->count();
  if (from < 0 || from < samples_ - static_cast<std::int64_t>(raw_.size()) || from + static_cast<std::int64_t>(count) > samples_) {
    return std::numeric_limits<double>::quiet_NaN();  // not all of it is still (or yet) held
  }
  std::vector<float> heard(count);
  for (std::size_t k = 0; k < count; ++k) heard[k] = raw_[static_cast<std::size_t>(from + static_cast<std::int64_t>(k)) & mask_];
  return (static_cast<double>(from) - reference_.offset) / fs + timer_->Time(heard.data());
}

}  // namespace nava_modem
