#include "nava_modem/room_carrier_sense.h"

#include <algorithm>
#include <cmath>

#include "nava_modem/room_phy.h"

namespace nava_modem {
namespace {

using namespace room_phy;

constexpr double kLevelSeconds = 0.010;
constexpr double kStepSeconds = 0.001;
// Busy air ends after a symbol's time of quiet; shorter stretches are clicks, not noise.
constexpr double kBusyRelease = kSymbolSeconds;
constexpr double kBusyMinimum = kSymbolSeconds;

}  // namespace

RoomCarrierSense::RoomCarrierSense(double sample_rate)
    : level_(sample_rate, kChirpLowHz - 100.0, kHighestHz + 600.0, kLevelSeconds),
      busy_(kBusyRelease, kBusyMinimum),
      step_(std::max<std::int64_t>(1, std::llround(kStepSeconds * sample_rate))) {}

double RoomCarrierSense::quiet_from() const { return busy_.last_loud() + kBusyRelease; }

}  // namespace nava_modem
