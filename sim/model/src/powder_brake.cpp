#include "wavebench/model/powder_brake.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::model {

PowderBrake::PowderBrake(const PowderBrakeParams& p) : p_(p) {
  if (!(p.torque_per_amp >= 0) || !(p.threshold_current >= 0) ||
      !(p.rated_current >= p.threshold_current)) {
    throw std::invalid_argument(
        "brake torque_per_amp/threshold_current/rated_current = " +
        std::to_string(p.torque_per_amp) + "/" + std::to_string(p.threshold_current) + "/" +
        std::to_string(p.rated_current) + ": expected >= 0 and rated >= threshold");
  }
  if (!(p.time_constant > 0) || !(p.holding_speed > 0) || !(p.falling_ratio > 0)) {
    throw std::invalid_argument(
        "brake time_constant/holding_speed/falling_ratio = " + std::to_string(p.time_constant) +
        "/" + std::to_string(p.holding_speed) + "/" + std::to_string(p.falling_ratio) +
        ": expected all > 0");
  }
  if (p.thermal_capacity > 0 && !(p.thermal_resistance > 0)) {
    throw std::invalid_argument(
        "brake.thermal_resistance = " + std::to_string(p.thermal_resistance) +
        " K/W: expected > 0 with a thermal capacity");
  }
}

double PowderBrake::rising_curve(double current) const noexcept {
  const double i = std::clamp(std::abs(current), p_.threshold_current, p_.rated_current);
  return p_.torque_per_amp * (i - p_.threshold_current);
}

double PowderBrake::falling_curve(double current) const noexcept {
  return p_.falling_ratio * rising_curve(current);
}

double PowderBrake::capacity_rate(double capacity) const noexcept {
  const double a = rising_curve(p_.current_setpoint);
  const double b = falling_curve(p_.current_setpoint);
  const double target = std::clamp(capacity, std::min(a, b), std::max(a, b));
  return (target - capacity) / p_.time_constant;
}

double PowderBrake::torque(double capacity, double omega) const noexcept {
  return capacity * std::tanh(omega / p_.holding_speed);
}

double PowderBrake::temperature_rate(double temperature, double slip_power) const noexcept {
  return (slip_power - (temperature - p_.ambient_temperature) / p_.thermal_resistance) /
         p_.thermal_capacity;
}

}  // namespace wavebench::model
