#include "world_sim/battery.h"

#include <gtest/gtest.h>

namespace world_sim {
namespace {

TEST(Battery, DrainsWithTimeAndMotion) {
  BatteryModel m;
  m.idle_drain = 0.001;
  m.motion_drain = 0.01;
  EXPECT_NEAR(StepBattery(0.5, m, 10.0, 0.0, false), 0.49, 1e-12);
  EXPECT_NEAR(StepBattery(0.5, m, 10.0, 2.0, false), 0.47, 1e-12);
  EXPECT_DOUBLE_EQ(StepBattery(0.001, m, 10.0, 0.0, false), 0.0);
}

TEST(Battery, ChargesWhileDocked) {
  BatteryModel m;
  m.charge_rate = 0.01;
  EXPECT_NEAR(StepBattery(0.5, m, 10.0, 0.0, true), 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(StepBattery(0.95, m, 10.0, 0.0, true), 1.0);
}

TEST(Battery, VoltageIsLinearInLevel) {
  BatteryModel m;
  EXPECT_DOUBLE_EQ(BatteryVoltage(0.0, m), m.empty_voltage);
  EXPECT_DOUBLE_EQ(BatteryVoltage(1.0, m), m.full_voltage);
  EXPECT_DOUBLE_EQ(BatteryVoltage(0.5, m), 0.5 * (m.empty_voltage + m.full_voltage));
}

}  // namespace
}  // namespace world_sim
