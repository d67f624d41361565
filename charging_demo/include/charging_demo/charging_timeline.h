#pragma once

#include <string>

#include "charging_demo/charging_trial.h"

namespace charging_demo {

// Draws one trial as a timeline and writes it as PNG: a lane per robot, coloured by the phase
// of the behaviour over time (duty, seek, approach, wait, dock, charge, undock), with the
// battery level drawn across the lane (bottom empty, top full) and the low-battery threshold
// dashed; a legend and a time axis in minutes. Throws std::runtime_error naming the path when
// it cannot be written.
void WriteChargingTimeline(const std::string& path, const ChargingTrialResult& trial,
                           double low_battery, const std::string& title);

}  // namespace charging_demo
