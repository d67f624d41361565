#pragma once

#include "world_sim/world_config.h"

namespace world_sim {

// Battery level (0 to 1) after dt seconds in which the robot drove `distance` metres, charging
// instead of draining while docked. Clamped to [0, 1].
double StepBattery(double level, const BatteryModel& model, double dt, double distance, bool docked);

// Terminal voltage at a level, linear between the model's empty and full voltages.
double BatteryVoltage(double level, const BatteryModel& model);

}  // namespace world_sim
