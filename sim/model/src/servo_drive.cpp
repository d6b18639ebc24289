#include "wavebench/model/servo_drive.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace wavebench::model {

ServoDrive::ServoDrive(const ServoDriveInput& p) : p_(p) {
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
}

double ServoDrive::speed_command(double theta1) const noexcept {
  double w =
      p_.position_control ? p_.position_gain * (p_.position_setpoint - theta1) : p_.speed_setpoint;
  if (p_.speed_limit > 0) w = std::clamp(w, -p_.speed_limit, p_.speed_limit);
  return w;
}

ServoOutput ServoDrive::evaluate(double theta1, double omega1, double integral) const noexcept {
  const double error = speed_command(theta1) - omega1;
  const double ti = p_.velocity_integral_time;
  const double demand = p_.velocity_gain * (error + (ti > 0 ? integral / ti : 0.0));
  ServoOutput out;
  out.torque = demand;
  out.integral_rate = ti > 0 ? error : 0.0;
  if (p_.torque_limit > 0 && std::abs(demand) > p_.torque_limit) {
    out.torque = demand > 0 ? p_.torque_limit : -p_.torque_limit;
    if (error * demand > 0) out.integral_rate = 0.0;
  }
  return out;
}

}  // namespace wavebench::model
