#include "world_sim/battery.h"

#include <algorithm>

namespace world_sim {

double StepBattery(double level, const BatteryModel& model, double dt, double distance, bool docked) {
  const double change = docked ? model.charge_rate * dt
                               : -(model.idle_drain * dt + model.motion_drain * distance);
  return std::clamp(level + change, 0.0, 1.0);
}

double BatteryVoltage(double level, const BatteryModel& model) {
  return model.empty_voltage + level * (model.full_voltage - model.empty_voltage);
}

}  // namespace world_sim
