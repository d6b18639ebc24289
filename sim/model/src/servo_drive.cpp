#include "wavebench/model/servo_drive.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace wavebench::model {
namespace {

const ServoDriveInput& validated(const ServoDriveInput& p) {
  if (!(p.velocity_gain > 0)) {
    throw std::invalid_argument("input.velocity_gain = " + std::to_string(p.velocity_gain) +
                                " N*m*s/rad: expected > 0");
  }
  if (p.velocity_integral_time < 0 || p.torque_limit < 0 || p.speed_limit < 0) {
    throw std::invalid_argument("input velocity_integral_time/torque_limit/speed_limit = " +
                                std::to_string(p.velocity_integral_time) + "/" +
                                std::to_string(p.torque_limit) + "/" +
                                std::to_string(p.speed_limit) + ": expected >= 0 (0 = off)");
  }
  return p;
}

double limit_or_none(double limit) {
  return limit > 0 ? limit : PiController::kNoLimit;
}

}  // namespace

ServoDrive::ServoDrive(const ServoDriveInput& p)
    : p_(validated(p)),
      position_loop_(p.position_gain, 0),
      velocity_loop_(p.velocity_gain, p.velocity_integral_time) {}

double ServoDrive::speed_command(double theta1) const noexcept {
  const double limit = limit_or_none(p_.speed_limit);
  if (p_.position_control)
    return position_loop_.evaluate(p_.position_setpoint - theta1, 0, limit).value;
  return std::clamp(p_.speed_setpoint, -limit, limit);
}

ServoOutput ServoDrive::evaluate(double theta1, double omega1, double integral) const noexcept {
  const PiOutput v = velocity_loop_.evaluate(speed_command(theta1) - omega1, integral,
                                             limit_or_none(p_.torque_limit));
  return {v.value, v.integral_rate};
}

}  // namespace wavebench::model
