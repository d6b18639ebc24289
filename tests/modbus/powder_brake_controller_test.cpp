#include "wavebench/simdevices/powder_brake_controller.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "wavebench/modbus/register_codec.hpp"

namespace wavebench::simdevices {
namespace {

namespace reg = brake_registers;

void write_u16(PowderBrakeController& c, int address, uint16_t v) {
  ASSERT_TRUE(c.write_holding(address, 1, &v));
}
void write_f32(PowderBrakeController& c, int address, double v) {
  const modbus::RegisterSpec s{modbus::RegisterTable::holding, address, modbus::DataType::float32};
  const auto regs = modbus::encode_value(s, modbus::WordOrder::abcd, v);
  ASSERT_TRUE(c.write_holding(address, 2, regs.data()));
}
double input_f32(const PowderBrakeController& c, int address) {
  const modbus::RegisterSpec s{modbus::RegisterTable::input, address, modbus::DataType::float32};
  return modbus::decode_value(s, modbus::WordOrder::abcd, &c.input()[static_cast<size_t>(address)]);
}
uint16_t status(const PowderBrakeController& c) {
  return c.input()[reg::status];
}

TEST(PowderBrakeController, CurrentSetpointWithRamp) {
  PowderBrakeController c;
  write_f32(c, reg::setpoint_ramp, 2.0);  // A/s
  write_f32(c, reg::setpoint, 1.0);
  c.step(0.1);
  EXPECT_EQ(input_f32(c, reg::coil_current), 0.0);  // not enabled
  write_u16(c, reg::control, reg::control_enable);
  c.step(0.25);
  EXPECT_NEAR(input_f32(c, reg::coil_current), 0.5, 1e-6);
  EXPECT_TRUE(status(c) & reg::status_output_on);
  EXPECT_FALSE(status(c) & reg::status_at_setpoint);
  c.step(0.25);
  c.step(0.25);
  EXPECT_NEAR(input_f32(c, reg::coil_current), 1.0, 1e-6);
  c.step(5.0);
  EXPECT_NEAR(input_f32(c, reg::torque), 50.0, 1e-4);
  EXPECT_TRUE(status(c) & reg::status_at_setpoint);
  // Disabling is immediate, not ramped.
  write_u16(c, reg::control, 0);
  c.step(0.001);
  EXPECT_EQ(input_f32(c, reg::coil_current), 0.0);
  EXPECT_FALSE(status(c) & reg::status_output_on);
}

TEST(PowderBrakeController, TorqueModeUsesTheStaticCurve) {
  PowderBrakeController c;
  write_f32(c, reg::setpoint, 30.0);
  write_u16(c, reg::control, reg::control_enable | reg::control_torque_mode);
  c.step(5.0);
  EXPECT_NEAR(input_f32(c, reg::coil_current), 0.6, 1e-6);
  EXPECT_NEAR(input_f32(c, reg::torque), 30.0, 1e-4);
}

TEST(PowderBrakeController, WatchdogTripsWhenHeartbeatsStop) {
  PowderBrakeController c;
  write_u16(c, reg::watchdog_ms, 200);
  write_f32(c, reg::setpoint, 1.0);
  write_u16(c, reg::control, reg::control_enable);
  for (uint16_t i = 1; i <= 20; ++i) {
    c.step(0.1);
    write_u16(c, reg::heartbeat, i);
  }
  EXPECT_EQ(c.alarm_code(), reg::alarm_none);
  EXPECT_TRUE(status(c) & reg::status_output_on);
  c.step(0.15);
  EXPECT_EQ(c.alarm_code(), reg::alarm_none);
  c.step(0.1);  // 250 ms without a heartbeat
  EXPECT_EQ(c.alarm_code(), reg::alarm_watchdog);
  EXPECT_TRUE(status(c) & reg::status_watchdog_tripped);
  EXPECT_TRUE(status(c) & reg::status_alarm);
  EXPECT_FALSE(status(c) & reg::status_output_on);
  EXPECT_EQ(c.input()[reg::alarm_code], reg::alarm_watchdog);
  EXPECT_EQ(c.holding()[reg::control] & reg::control_enable, 0);
  EXPECT_EQ(input_f32(c, reg::coil_current), 0.0);
  // Reset clears it and the reset bit does not stick.
  write_u16(c, reg::control, reg::control_reset_alarm);
  EXPECT_EQ(c.alarm_code(), reg::alarm_none);
  EXPECT_EQ(c.holding()[reg::control] & reg::control_reset_alarm, 0);
  c.step(0.1);
  EXPECT_FALSE(status(c) & reg::status_watchdog_tripped);
}

TEST(PowderBrakeController, OverTemperatureAlarmAtTheLimit) {
  PowderBrakeController c;
  write_f32(c, reg::setpoint, 2.0);
  write_u16(c, reg::control, reg::control_enable);
  c.step(5.0);
  c.physics().set_output_speed(3.0);  // 300 W of slip
  double t = 0.0;
  while (c.alarm_code() == reg::alarm_none && t < 3600.0) {
    c.step(0.5);
    t += 0.5;
  }
  EXPECT_EQ(c.alarm_code(), reg::alarm_over_temperature);
  EXPECT_GE(c.physics().temperature(), 80.0);
  EXPECT_LT(c.physics().temperature(), 80.5);
  EXPECT_TRUE(status(c) & reg::status_over_temperature);
  EXPECT_FALSE(c.output_on());
  // Still hot: reset does not clear it.
  write_u16(c, reg::control, reg::control_reset_alarm);
  EXPECT_EQ(c.alarm_code(), reg::alarm_over_temperature);
  c.physics().set_temperature(70.0);
  write_u16(c, reg::control, reg::control_reset_alarm);
  EXPECT_EQ(c.alarm_code(), reg::alarm_none);
}

TEST(PowderBrakeController, CoilOpenRaisesAlarm) {
  PowderBrakeController c;
  write_f32(c, reg::setpoint, 1.0);
  write_u16(c, reg::control, reg::control_enable);
  c.step(0.1);
  c.physics().set_coil_open(true);
  c.step(0.01);
  EXPECT_EQ(c.alarm_code(), reg::alarm_coil_open);
  EXPECT_TRUE(status(c) & reg::status_coil_open);
}

TEST(PowderBrakeController, RejectsWritesOutsideTheTable) {
  PowderBrakeController c;
  const uint16_t v[2] = {1, 2};
  EXPECT_FALSE(c.write_holding(31, 2, v));
  EXPECT_TRUE(c.write_holding(30, 2, v));
}

}  // namespace
}  // namespace wavebench::simdevices
